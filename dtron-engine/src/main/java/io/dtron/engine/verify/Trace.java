package io.dtron.engine.verify;

import io.dtron.engine.JsonString;
import java.math.BigDecimal;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * A diagnostic trace: a path of the zone graph from the initial state, symbolic (locations, variables, zone and
 * the edges of each transition) and concrete (delays and transitions at exact times).
 *
 * @param states      the symbolic states, the initial one first; after each transition, time has passed as far
 *                    as the invariants allow (in the last state, the part that satisfies the query's property)
 * @param transitions the transitions; transition {@code i} leads from state {@code i} to state {@code i + 1}
 * @param loopStart   for a path that ends in a cycle, the index of the state the last transition leads back to
 *                    (its states repeat forever); else -1
 * @param end         how a path of a liveness counterexample or witness ends ({@code "a cycle back to state 2"},
 *                    {@code "a deadlock"}, {@code "time passing forever"}), or null for a reachability trace
 * @param concrete    the same path with concrete delays, or empty when none could be computed
 */
public record Trace(List<State> states, List<Transition> transitions, int loopStart, String end,
                    List<ConcreteStep> concrete) {

    public Trace {
        states = List.copyOf(states);
        transitions = List.copyOf(transitions);
        concrete = List.copyOf(concrete);
        if (transitions.size() != states.size() - 1) {
            throw new IllegalArgumentException(states.size() + " states need " + (states.size() - 1)
                    + " transitions, not " + transitions.size());
        }
    }

    /**
     * A symbolic state.
     *
     * @param locations each process's location as {@code Process.location}
     * @param variables each integer variable slot by name ({@code id}, {@code Gate.list[2]})
     * @param zone      the clock constraints, e.g. {@code x>10, y<=5, x-y<3}
     */
    public record State(List<String> locations, Map<String, Integer> variables, String zone) {
        public State {
            locations = List.copyOf(locations);
            variables = Map.copyOf(new LinkedHashMap<>(variables));
        }
    }

    /**
     * A transition: the edges that take part, as {@code Process: source -> target}, and the channel.
     *
     * @param channel the channel synchronised on ({@code appr[1]}), or null for an internal edge
     * @param edges   the edges, in the order their updates run
     */
    public record Transition(String channel, List<String> edges) {
        public Transition {
            edges = List.copyOf(edges);
        }

        /** The transition as one line: {@code appr[1]: Train(1): Safe -> Appr, Gate: Free -> Occ}. */
        @Override
        public String toString() {
            return (channel == null ? "" : channel + ": ") + String.join(", ", edges);
        }
    }

    /**
     * One concrete step: a delay, then a transition (none for a final delay).
     *
     * @param delay      the delay before the transition, in model time units
     * @param time       the time of the transition since the start
     * @param clocks     each clock's value just before the transition, after the delay
     * @param transition the transition taken, or null for the final delay into the last state
     */
    public record ConcreteStep(BigDecimal delay, BigDecimal time, Map<String, BigDecimal> clocks,
                               Transition transition) {
        public ConcreteStep {
            clocks = Map.copyOf(clocks);
        }
    }

    /** The trace for people: the symbolic path, then the concrete one. */
    public String toText() {
        StringBuilder sb = new StringBuilder();
        for (int i = 0; i < states.size(); i++) {
            State s = states.get(i);
            sb.append("  state ").append(i).append(": ").append(String.join(", ", s.locations()));
            if (!s.variables().isEmpty()) {
                sb.append("; ").append(variables(s));
            }
            sb.append("; ").append(s.zone()).append('\n');
            if (i < transitions.size()) {
                sb.append("    --> ").append(transitions.get(i)).append('\n');
            }
        }
        if (end != null) {
            sb.append("  and then ").append(end).append('\n');
        }
        if (!concrete.isEmpty()) {
            sb.append("  concrete:\n");
            for (ConcreteStep c : concrete) {
                sb.append("    delay ").append(c.delay().toPlainString()).append(", at ").append(c.time().toPlainString());
                if (c.transition() != null) {
                    sb.append(": ").append(c.transition());
                }
                sb.append(" (").append(clockValues(c)).append(")\n");
            }
        }
        return sb.toString();
    }

    /** The trace as one JSON object: {@code {"states":[...],"transitions":[...],"loopStart":-1,...}}. */
    public String toJson() {
        StringBuilder sb = new StringBuilder("{\"states\":[");
        for (int i = 0; i < states.size(); i++) {
            State s = states.get(i);
            sb.append(i == 0 ? "" : ",").append("{\"locations\":[");
            for (int l = 0; l < s.locations().size(); l++) {
                sb.append(l == 0 ? "" : ",").append(quote(s.locations().get(l)));
            }
            sb.append("],\"variables\":{");
            boolean first = true;
            for (Map.Entry<String, Integer> v : sortedVariables(s).entrySet()) {
                sb.append(first ? "" : ",").append(quote(v.getKey())).append(':').append(v.getValue());
                first = false;
            }
            sb.append("},\"zone\":").append(quote(s.zone())).append('}');
        }
        sb.append("],\"transitions\":[");
        for (int i = 0; i < transitions.size(); i++) {
            sb.append(i == 0 ? "" : ",").append(transitionJson(transitions.get(i)));
        }
        sb.append("],\"loopStart\":").append(loopStart).append(",\"end\":").append(end == null ? "null" : quote(end));
        sb.append(",\"concrete\":[");
        for (int i = 0; i < concrete.size(); i++) {
            ConcreteStep c = concrete.get(i);
            sb.append(i == 0 ? "" : ",").append("{\"delay\":").append(c.delay().toPlainString()).append(",\"time\":")
                    .append(c.time().toPlainString()).append(",\"clocks\":{");
            boolean first = true;
            for (Map.Entry<String, BigDecimal> v : new java.util.TreeMap<>(c.clocks()).entrySet()) {
                sb.append(first ? "" : ",").append(quote(v.getKey())).append(':').append(v.getValue().toPlainString());
                first = false;
            }
            sb.append("},\"transition\":").append(c.transition() == null ? "null" : transitionJson(c.transition()))
                    .append('}');
        }
        return sb.append("]}").toString();
    }

    private static String variables(State s) {
        StringBuilder sb = new StringBuilder();
        for (Map.Entry<String, Integer> v : sortedVariables(s).entrySet()) {
            sb.append(sb.length() == 0 ? "" : ", ").append(v.getKey()).append('=').append(v.getValue());
        }
        return sb.toString();
    }

    private static Map<String, Integer> sortedVariables(State s) {
        return new java.util.TreeMap<>(s.variables());
    }

    private static String clockValues(ConcreteStep c) {
        StringBuilder sb = new StringBuilder();
        for (Map.Entry<String, BigDecimal> v : new java.util.TreeMap<>(c.clocks()).entrySet()) {
            sb.append(sb.length() == 0 ? "" : ", ").append(v.getKey()).append('=').append(v.getValue().toPlainString());
        }
        return sb.toString();
    }

    private static String transitionJson(Transition t) {
        StringBuilder sb = new StringBuilder("{\"channel\":").append(t.channel() == null ? "null" : quote(t.channel()))
                .append(",\"edges\":[");
        for (int e = 0; e < t.edges().size(); e++) {
            sb.append(e == 0 ? "" : ",").append(quote(t.edges().get(e)));
        }
        return sb.append("]}").toString();
    }

    private static String quote(String s) {
        return JsonString.quote(s);
    }
}
