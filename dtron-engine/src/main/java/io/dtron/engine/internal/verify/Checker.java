package io.dtron.engine.internal.verify;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.ClockLimits;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.StateText;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.SearchOrder;
import io.dtron.engine.verify.Trace;
import io.dtron.engine.verify.VerificationResult;
import io.dtron.engine.verify.VerificationResult.Outcome;
import io.dtron.engine.verify.VerificationResult.Statistics;
import io.dtron.engine.verify.VerifierOptions;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Network;
import java.math.BigDecimal;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Collections;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.function.BiFunction;
import java.util.function.Function;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Checks queries on one network. Reachability ({@code E<>}, {@code A[]}) is a passed/waiting search with zone
 * inclusion on both sides (a new state included in a stored one is dropped; stored states included in a new one
 * are dropped, and skipped if still waiting). Liveness ({@code E[]}, {@code A<>}, {@code -->}) is a depth-first
 * search for a maximal path inside the states that satisfy the property: a cycle (a state met again on the
 * search stack), a state where time can pass forever, or a deadlock; for {@code -->}, one such search from each
 * reachable state satisfying the premise, sharing the states already shown to have none.
 */
public final class Checker {
    private static final Logger LOG = LoggerFactory.getLogger("io.dtron.engine.verify");
    /** The zone of the passed list's keys, which stand for locations and variables only. */
    private static final Dbm NO_ZONE = Dbm.zero(1);

    private final Network network;
    private final VerifierOptions options;
    private final Semantics semantics;
    private final PropertyCompiler compiler;
    private final String[] clockNames;

    /** A checker of {@code network}'s queries. */
    public Checker(Network network, VerifierOptions options) {
        this.network = network;
        this.options = options;
        this.semantics = new Semantics(network, 1, false);
        this.compiler = new PropertyCompiler(network);
        this.clockNames = new String[semantics.dimension()];
        clockNames[0] = "0";
        for (var c : network.clocks()) {
            for (int i = c.index(); i < c.index() + c.type().clocks(); i++) {
                clockNames[i] = c.elementName(i);
            }
        }
    }

    /** The network checked. */
    Network network() {
        return network;
    }

    /** The semantics the searches run on. */
    Semantics semantics() {
        return semantics;
    }

    /** The options of the searches. */
    VerifierOptions options() {
        return options;
    }

    /** The names of the clocks by number, {@code "0"} for the reference clock. */
    String[] clockNames() {
        return clockNames;
    }

    /**
     * Checks {@code query}.
     *
     * @throws io.dtron.engine.verify.QueryException when a property does not compile
     * @throws UnsupportedModelException on a model error met during the search
     */
    public VerificationResult verify(Query query) {
        if (query.kind() == Query.Kind.UNSUPPORTED) {
            return new VerificationResult(query, Outcome.SKIPPED, query.reason(), Statistics.NONE, null);
        }
        boolean negate = query.kind() == Query.Kind.ALWAYS_GLOBALLY || query.kind() == Query.Kind.ALWAYS_EVENTUALLY;
        Property p = compiler.compile(query.text(), query.property(), query.column(), negate);
        // the target ends the query: p --> p has its second p at the end, not where indexOf finds it
        Property q = query.target() == null ? null
                : compiler.compile(query.text(), query.target(), (query.text().endsWith(query.target())
                        ? query.text().length() - query.target().length() : query.text().indexOf(query.target())) + 1,
                        true);
        Budget budget = new Budget(query.text(), options.timeLimit(), options.memoryLimitBytes(),
                options.progressInterval());
        try {
            return switch (query.kind()) {
                case EXISTS_EVENTUALLY, ALWAYS_GLOBALLY -> reachability(query, p, budget);
                default -> liveness(query, p, q, budget);
            };
        } catch (Budget.LimitReached e) {
            return new VerificationResult(query, Outcome.UNKNOWN, e.getMessage(), statistics(budget), null);
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while checking '" + query.text() + "': " + e.format());
        }
    }

    Statistics statistics(Budget b) {
        return new Statistics(b.explored, b.stored, b.elapsed(), b.peakMemory());
    }

    ZoneGraph graph(boolean regionPreserving, List<Property> properties) {
        List<int[]> atoms = new ArrayList<>();
        boolean exact = true;
        for (Property p : properties) {
            if (p != null) {
                exact &= p.clockAtoms(atoms);
            }
        }
        ClockLimits limits = exact ? ClockLimits.of(network, semantics.dimension(), atoms) : null;
        if (limits == null) {
            LOG.warn("{}: clocks are compared with clocks or with variables, so states are not extrapolated: the"
                    + " search may not end (use a time limit)", network.file());
        }
        return new ZoneGraph(semantics, limits, regionPreserving);
    }

    // ================================================================ reachability

    /**
     * A stored state, with its parent and which of the parent's successors it is (in the order the semantics
     * gives them), for traces: the move itself is found again when a trace is built.
     */
    static final class Node {
        /** The locations and variables (shared by the nodes of the same discrete state; its zone is unused). */
        final SymState discrete;
        /** The zone, packed when its bounds fit in shorts; both null once covered by a larger zone. */
        short[] packed;
        Dbm zone;
        final Node parent;
        final int successor;
        boolean covered;

        Node(SymState discrete, Dbm zone, Node parent, int successor) {
            this.discrete = discrete;
            this.packed = zone.pack();
            this.zone = packed == null ? zone : null;
            this.parent = parent;
            this.successor = successor;
        }

        /** The state (a new object on each call when the zone is packed). */
        SymState state(int dimension) {
            return discrete.withZone(zone != null ? zone : Dbm.unpack(dimension, packed));
        }

        /** Whether {@code z} is included in this node's zone. */
        boolean includes(Dbm z) {
            return zone != null ? z.isSubsetOf(zone) : z.isSubsetOf(packed);
        }

        /** Whether this node's zone is included in {@code z}. */
        boolean isIncludedIn(Dbm z) {
            return zone != null ? zone.isSubsetOf(z) : z.includes(packed);
        }

        void cover() {
            covered = true;
            packed = null;
            zone = null;
        }
    }

    /** The discrete part of a state as a hash key. */
    private record Discrete(SymState state) {
        @Override
        public boolean equals(Object o) {
            return o instanceof Discrete d && d.state.sameDiscrete(state);
        }

        @Override
        public int hashCode() {
            return state.discreteHash();
        }
    }

    /** A whole state (discrete part and zone) as a hash key. */
    record Exact(SymState state, int hash) {
        Exact(SymState state) {
            this(state, 31 * state.discreteHash() + state.zone().hashCode());
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof Exact e && e.hash == hash && e.state.sameDiscrete(state)
                    && e.state.zone().equals(state.zone());
        }

        @Override
        public int hashCode() {
            return hash;
        }
    }

    /** Where {@code E<> target} was found: the node and the part of its zone that satisfies the target. */
    record Found(Node node, Dbm part) {
    }

    private VerificationResult reachability(Query query, Property target, Budget budget) {
        ZoneGraph graph = graph(target.mentionsDeadlock(), List.of(target));
        Property.StateInfo info = graph::deadlocked;
        Found found = search(graph, target, info, budget, null);
        boolean exists = found != null;
        boolean holds = query.kind() == Query.Kind.EXISTS_EVENTUALLY ? exists : !exists;
        Trace trace = null;
        if (exists) {
            List<Node> path = path(found.node);
            Function<SymState, Dbm> part = target.dependsOnZone() ? exact -> firstPart(target, exact, graph) : null;
            trace = trace(graph, path, found.part, -1, null, part);
        }
        return new VerificationResult(query, holds ? Outcome.SATISFIED : Outcome.VIOLATED, null, statistics(budget),
                trace);
    }

    private static Dbm firstPart(Property p, SymState exact, ZoneGraph graph) {
        List<Dbm> parts = new ArrayList<>();
        p.restrict(exact, exact.zone(), graph::deadlocked, parts);
        return parts.isEmpty() ? null : parts.get(0);
    }

    /**
     * The passed/waiting search: the first stored state where {@code target} holds somewhere (null: none), or,
     * with a {@code visitor}, every stored state visited (the visitor may stop the search by returning a result).
     */
    Found search(ZoneGraph graph, Property target, Property.StateInfo info, Budget budget,
                         BiFunction<Node, SymState, Found> visitor) {
        Map<Discrete, List<Node>> passed = new HashMap<>();
        ArrayDeque<Node> waiting = new ArrayDeque<>();
        boolean depthFirst = options.order() == SearchOrder.DEPTH_FIRST;
        int dimension = graph.dimension();
        SymState initial = graph.initial();
        Node init = new Node(initial.withZone(NO_ZONE), initial.zone(), null, -1);
        Found hit = check(init, initial, target, info, visitor);
        if (hit != null) {
            return hit;
        }
        passed.computeIfAbsent(new Discrete(init.discrete), k -> new ArrayList<>()).add(init);
        budget.stored = 1;
        waiting.add(init);
        Found[] result = new Found[1];
        while (!waiting.isEmpty() && result[0] == null) {
            Node n = depthFirst ? waiting.pollLast() : waiting.pollFirst();
            if (n.covered) {
                continue;
            }
            budget.explore();
            int[] index = {0};
            graph.successors(n.state(dimension), (move, next) -> {
                int successor = index[0]++;
                if (result[0] != null) {
                    return;
                }
                List<Node> same = passed.get(new Discrete(next));
                SymState discrete;
                if (same == null) {
                    // the key keeps the locations and variables (shared with the nodes), not the zone
                    discrete = next.withZone(NO_ZONE);
                    same = new ArrayList<>(2);
                    passed.put(new Discrete(discrete), same);
                } else {
                    discrete = same.get(0).discrete;
                }
                Dbm zone = next.zone();
                for (int i = 0; i < same.size(); i++) {
                    if (same.get(i).includes(zone)) {
                        return;
                    }
                }
                for (int i = same.size() - 1; i >= 0; i--) {
                    Node old = same.get(i);
                    if (old.isIncludedIn(zone)) {
                        old.cover();
                        same.set(i, same.get(same.size() - 1));
                        same.remove(same.size() - 1);
                        budget.stored--;
                    }
                }
                Node child = new Node(discrete, zone, n, successor);
                same.add(child);
                budget.stored++;
                waiting.add(child);
                result[0] = check(child, next, target, info, visitor);
            });
        }
        return result[0];
    }

    /** Checks the state {@code s} of node {@code n} when it is stored. */
    private static Found check(Node n, SymState s, Property target, Property.StateInfo info,
                               BiFunction<Node, SymState, Found> visitor) {
        if (visitor != null) {
            return visitor.apply(n, s);
        }
        if (!target.dependsOnZone()) {
            return target.holds(s) ? new Found(n, s.zone()) : null;
        }
        List<Dbm> parts = new ArrayList<>(2);
        target.restrict(s, s.zone(), info, parts);
        return parts.isEmpty() ? null : new Found(n, parts.get(0));
    }

    static List<Node> path(Node last) {
        List<Node> path = new ArrayList<>();
        for (Node n = last; n != null; n = n.parent) {
            path.add(n);
        }
        Collections.reverse(path);
        return path;
    }

    // ================================================================ liveness

    private static final String DEADLOCK_END = "a deadlock";

    /** A maximal path inside a property: the states, the moves between them, and how it ends. */
    record Lasso(List<SymState> states, List<Semantics.Move> moves, int loopStart, String end) {
    }

    private VerificationResult liveness(Query query, Property p, Property q, Budget budget) {
        Property inside = q == null ? p : q;
        ZoneGraph graph = graph(true, List.of(p, inside));
        // maximal paths inside the property: into a cycle, or to a state where time passes forever or that stops
        CycleSearch maximal = new CycleSearch((s, sink) -> successorsInside(graph, s, inside, sink),
                s -> graph.timeDiverges(s) ? "time passing forever" : stops(graph, s) ? DEADLOCK_END : null, budget);
        if (q == null) {
            Lasso lasso = null;
            for (SymState start : insideParts(graph, graph.semantics().initial(), inside)) {
                lasso = maximal.from(start);
                if (lasso != null) {
                    break;
                }
            }
            budget.stored = maximal.finished();
            boolean found = lasso != null;
            boolean holds = query.kind() == Query.Kind.EXISTS_GLOBALLY ? found : !found;
            Trace trace = found ? trace(graph, List.of(), lasso) : null;
            return new VerificationResult(query, holds ? Outcome.SATISFIED : Outcome.VIOLATED, null,
                    statistics(budget), trace);
        }
        // p --> q: from every valuation of a reachable state where p holds, no maximal path avoiding q
        Lasso[] witness = new Lasso[1];
        Found found = search(graph, null, graph::deadlocked, budget, (n, s) -> {
            for (Dbm premise : parts(graph, p, s)) {
                for (SymState start : insideParts(graph, s.withZone(premise), inside)) {
                    Lasso lasso = maximal.from(start);
                    if (lasso != null) {
                        witness[0] = lasso;
                        return new Found(n, s.zone());
                    }
                }
            }
            return null;
        });
        budget.stored += maximal.finished();
        if (found == null) {
            return new VerificationResult(query, Outcome.SATISFIED, null, statistics(budget), null);
        }
        List<Node> prefix = path(found.node);
        return new VerificationResult(query, Outcome.VIOLATED, null, statistics(budget),
                trace(graph, prefix, witness[0]));
    }

    /** The part of {@code s}'s zone where {@code p} holds, as zones (copies). */
    private static List<Dbm> parts(ZoneGraph graph, Property p, SymState s) {
        if (!p.dependsOnZone()) {
            return p.holds(s) ? List.of(s.zone().copy()) : List.of();
        }
        List<Dbm> out = new ArrayList<>();
        p.restrict(s, s.zone(), graph::deadlocked, out);
        out.replaceAll(Dbm::copy);
        return out;
    }

    /**
     * The states a path inside {@code inside} reaches from the valuations of {@code entry} (a state just entered,
     * not yet delayed) by letting time pass without leaving {@code inside} at any instant, each extrapolated: one
     * state per zone of that union of zones (empty when {@code inside} does not hold at entry).
     */
    private List<SymState> insideParts(ZoneGraph graph, SymState entry, Property inside) {
        SymState closure = entry.copy();
        if (!graph.semantics().delay(closure)) {
            return List.of();
        }
        List<Dbm> in = parts(graph, inside, closure);
        if (inside.dependsOnZone() && !in.isEmpty() && graph.semantics().mayDelay(closure)) {
            in = delayInside(entry.zone(), closure.zone(), in);
        }
        List<SymState> out = new ArrayList<>(in.size());
        for (Dbm z : in) {
            SymState part = closure.withZone(z);
            graph.extrapolate(part);
            out.add(part);
        }
        return out;
    }

    /**
     * The valuations {@code v + d} of {@code closure} (the delay closure of {@code entry} within the invariants)
     * with {@code v} in {@code entry} and every {@code v + d'}, {@code 0 <= d' <= d}, in {@code in} (a union of
     * zones within {@code closure}). With {@code B_j} the zones of {@code closure} outside {@code in}, a delay
     * avoids {@code B_j} when no point of {@code B_j} lies before {@code v + d} on its line ({@code closure}
     * minus {@code B_j}'s future), or when {@code v} itself lies after {@code B_j} (the future of the part of
     * {@code entry} in {@code B_j}'s future but not in {@code B_j}); as the shortest delay into a point avoids
     * every {@code B_j} as soon as some delay avoids each, the answer is the intersection over {@code j}.
     */
    static List<Dbm> delayInside(Dbm entry, Dbm closure, List<Dbm> in) {
        List<Dbm> outside = new ArrayList<>(List.of(closure));
        for (Dbm z : in) {
            outside = Zones.subtract(outside, z);
        }
        List<Dbm> result = List.of(closure);
        for (Dbm bad : outside) {
            Dbm future = bad.copy();
            future.up();
            List<Dbm> avoiding = new ArrayList<>(Zones.subtract(List.of(closure), future));
            Dbm after = entry.copy();
            if (after.intersect(future)) {
                for (Dbm z : Zones.subtract(List.of(after), bad)) {
                    Dbm later = z.copy();
                    later.up();
                    if (later.intersect(closure)) {
                        avoiding.add(later);
                    }
                }
            }
            List<Dbm> next = new ArrayList<>();
            for (Dbm r : result) {
                for (Dbm a : avoiding) {
                    Dbm both = r.copy();
                    if (both.intersect(a)) {
                        next.add(both);
                    }
                }
            }
            if (next.isEmpty()) {
                return next;
            }
            result = next;
        }
        return result;
    }

    /** The successors of {@code s} inside {@code inside} (a state {@link #insideParts} gave): their parts inside it. */
    private void successorsInside(ZoneGraph graph, SymState s, Property inside, ZoneGraph.Sink sink) {
        if (!inside.dependsOnZone()) {
            // the property does not change while time passes: a successor is inside it or not at all
            graph.successors(s, (m, next) -> {
                if (inside.holds(next)) {
                    sink.accept(m, next);
                }
            });
            return;
        }
        graph.semantics().moves(s, (m, next) -> {
            for (SymState part : insideParts(graph, next, inside)) {
                sink.accept(m, part);
            }
        });
    }

    /** Whether a path can end in {@code s}: see {@link #stopping}. */
    private static boolean stops(ZoneGraph graph, SymState s) {
        return !stopping(graph, s).isEmpty();
    }

    /**
     * The valuations of {@code s}'s zone where a path can end: deadlocked, and time cannot pass either (at an
     * invariant's bound {@code x <= c}, or time may not pass in {@code s}). Computed on the zone's delay closure,
     * since the part of a state inside a property may stop short of the moves and of the bound that time would
     * reach.
     */
    private static List<Dbm> stopping(ZoneGraph graph, SymState s) {
        SymState closure = s.copy();
        graph.semantics().delay(closure);
        Dbm zone = closure.zone();
        List<Dbm> atBound = new ArrayList<>();
        if (!graph.semantics().mayDelay(closure)) {
            atBound.add(s.zone());
        } else {
            for (int x = 1; x < graph.dimension(); x++) {
                int bound = zone.upperBound(x, 0);
                Dbm at = s.zone().copy();
                if (bound != Bound.INFINITY && !Bound.isStrict(bound)
                        && at.constrain(0, x, Bound.le(-Bound.value(bound)))) {
                    atBound.add(at);
                }
            }
        }
        List<Dbm> out = new ArrayList<>();
        for (Dbm dead : graph.deadlocked(closure)) {
            for (Dbm at : atBound) {
                Dbm both = dead.copy();
                if (both.intersect(at)) {
                    out.add(both);
                }
            }
        }
        return out;
    }

    // ================================================================ traces

    Trace trace(ZoneGraph graph, List<Node> path, Dbm lastPart, int loopStart, String end,
                        Function<SymState, Dbm> target) {
        List<SymState> states = new ArrayList<>();
        List<Semantics.Move> moves = new ArrayList<>();
        replay(graph, path, states, moves);
        SymState last = states.get(states.size() - 1).copy();
        last.zone().copyFrom(lastPart);
        states.set(states.size() - 1, last);
        return build(graph, states, moves, loopStart, end, target, null, null);
    }

    /** A liveness trace: the reachability prefix up to the lasso's start, then the lasso. */
    Trace trace(ZoneGraph graph, List<Node> prefix, Lasso lasso) {
        List<SymState> states = new ArrayList<>();
        List<Semantics.Move> moves = new ArrayList<>();
        if (!prefix.isEmpty()) {
            replay(graph, prefix, states, moves);
            states.remove(states.size() - 1);
        }
        int offset = states.size();
        states.addAll(lasso.states);
        moves.addAll(lasso.moves);
        // the concrete path keeps to the lasso's states, which lie inside the property; the first one is entered
        // before the premise of --> holds, at the end of the prefix
        List<Dbm> within = new ArrayList<>(Collections.nCopies(offset, (Dbm) null));
        for (SymState s : lasso.states) {
            within.add(s.zone());
        }
        List<Dbm> entering = new ArrayList<>(within);
        if (!prefix.isEmpty()) {
            entering.set(offset, null);
        }
        int loop = lasso.loopStart < 0 ? -1 : lasso.loopStart + offset;
        String end = loop < 0 ? lasso.end : lasso.end + loop;
        Function<SymState, Dbm> target = null;
        if (lasso.end.equals(DEADLOCK_END)) {
            // the concrete path goes on to where it stops
            Dbm last = lasso.states.get(lasso.states.size() - 1).zone();
            target = exact -> {
                Dbm part = exact.zone().copy();
                List<Dbm> stop = part.intersect(last) ? stopping(graph, exact.withZone(part)) : List.of();
                return stop.isEmpty() ? null : stop.get(0);
            };
        }
        return build(graph, states, moves, loop, end, target, within, entering);
    }

    /**
     * The states and moves of a path of nodes, found again from the initial state by taking each node's successor
     * number (covered nodes no longer hold their states).
     */
    private static void replay(ZoneGraph graph, List<Node> path, List<SymState> states, List<Semantics.Move> moves) {
        SymState s = graph.initial();
        states.add(s);
        for (int i = 1; i < path.size(); i++) {
            int wanted = path.get(i).successor;
            Semantics.Move[] move = new Semantics.Move[1];
            SymState[] next = new SymState[1];
            int[] index = {0};
            graph.successors(s, (m, successor) -> {
                if (index[0]++ == wanted) {
                    move[0] = m;
                    next[0] = successor;
                }
            });
            moves.add(move[0]);
            s = next[0];
            states.add(s);
        }
    }

    private Trace build(ZoneGraph graph, List<SymState> states, List<Semantics.Move> moves, int loopStart,
                        String end, Function<SymState, Dbm> target, List<Dbm> within, List<Dbm> entering) {
        List<Trace.State> symbolic = new ArrayList<>();
        for (SymState s : states) {
            symbolic.add(describe(s));
        }
        List<Trace.Transition> transitions = new ArrayList<>();
        for (Semantics.Move m : moves) {
            transitions.add(describe(m));
        }
        List<Trace.ConcreteStep> concrete = new ArrayList<>();
        List<Concretizer.Step> steps = new Concretizer(graph).concretize(moves, target, within, entering);
        if (steps.isEmpty() && within != null) {
            // the states' zones are extrapolated: the exact path may lie beside them, then only the moves count
            steps = new Concretizer(graph).concretize(moves, target, null, null);
            if (steps.isEmpty() && target != null) {
                steps = new Concretizer(graph).concretize(moves, null, null, null);
            }
        }
        BigDecimal time = BigDecimal.ZERO;
        for (int i = 0; i < steps.size(); i++) {
            Concretizer.Step step = steps.get(i);
            time = time.add(step.delay());
            Map<String, BigDecimal> clocks = new LinkedHashMap<>();
            for (int c = 1; c < clockNames.length; c++) {
                clocks.put(clockNames[c], step.clocks()[c]);
            }
            concrete.add(new Trace.ConcreteStep(step.delay(), time, clocks, i < transitions.size()
                    ? transitions.get(i) : null));
        }
        return new Trace(symbolic, transitions, loopStart, end, concrete);
    }

    private Trace.State describe(SymState s) {
        List<String> locations = StateText.locations(network, s);
        Map<String, Integer> variables = StateText.variables(network, s);
        return new Trace.State(locations, variables, s.zone().toString(clockNames));
    }

    private Trace.Transition describe(Semantics.Move m) {
        List<String> edges = new ArrayList<>();
        for (Semantics.Step step : m.steps()) {
            edges.add(semantics.describe(step));
        }
        return new Trace.Transition(m.channel() < 0 ? null : network.channelName(m.channel()), edges);
    }
}
