package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.sem.ClockLimits;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.verify.CoverTime;
import io.dtron.engine.verify.Query;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Network;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.PriorityQueue;

/**
 * The shortest time in which a run of the model can set every trap: a best-first search of the zone graph with a
 * global clock that no edge resets and no extrapolation abstracts, over pairs of a symbolic state and the set of
 * traps set so far on the path (a trap counts once it has held, even if the model clears it again), ordered by the
 * least value of the global clock. Time only grows along a path, so the first state popped with every trap set has
 * the least such value of all: the infimum of the times at which a run has set them all (reached exactly unless the
 * zone's bound is strict). The search stops there, at the state limit, or when nothing is left to explore (then no
 * run sets them all).
 */
public final class FastestCover {
    /** The bound the global clock's extrapolation keeps: far beyond any time a search reaches. */
    private static final int GLOBAL_LIMIT = 1 << 26;

    private FastestCover() {
    }

    /** A state of the search: the symbolic state, the traps set so far (a bit mask), the least global time. */
    private record Node(SymState state, long mask, long least, boolean strict) {
    }

    /** The discrete part of a state and its trap mask, as a key of the passed list. */
    private record Key(SymState state, long mask) {
        @Override
        public boolean equals(Object o) {
            return o instanceof Key k && k.mask == mask && k.state.sameDiscrete(state);
        }

        @Override
        public int hashCode() {
            return 31 * state.discreteHash() + Long.hashCode(mask);
        }
    }

    /**
     * The shortest time to set every one of {@code traps} (boolean expressions, each the name of a trap) in {@code
     * network}, exploring at most {@code maxStates} symbolic states.
     *
     * @throws UnsupportedModelException on a model error met during the search
     * @throws IllegalArgumentException  with more than 63 traps
     */
    public static CoverTime of(Network network, List<String> traps, long maxStates) {
        if (traps.size() > 63) {
            throw new IllegalArgumentException("at most 63 traps, not " + traps.size());
        }
        Semantics semantics = new Semantics(network, 1, true);
        int global = semantics.elapsedClock();
        List<StateProperty> set = new ArrayList<>();
        for (String t : traps) {
            set.add(StateProperty.goal(network, Query.parse("E<> " + t), 1));
        }
        List<int[]> atoms = List.of(new int[] {global, GLOBAL_LIMIT, 1}, new int[] {global, GLOBAL_LIMIT, 0});
        ZoneGraph graph = new ZoneGraph(semantics, ClockLimits.of(network, semantics.dimension(), atoms), false);
        long all = traps.size() == 63 ? Long.MAX_VALUE : (1L << traps.size()) - 1;
        PriorityQueue<Node> waiting = new PriorityQueue<>((a, b) -> a.least != b.least ? Long.compare(a.least,
                b.least) : Boolean.compare(a.strict, b.strict));
        Map<Key, List<Dbm>> passed = new HashMap<>();
        long explored = 0;
        try {
            SymState init = graph.initial();
            waiting.add(node(init, mask(set, init, 0), global));
            while (!waiting.isEmpty()) {
                Node n = waiting.poll();
                if (n.mask == all) {
                    return new CoverTime(CoverTime.Answer.FOUND, n.least, n.strict, explored);
                }
                List<Dbm> zones = passed.computeIfAbsent(new Key(n.state, n.mask), k -> new ArrayList<>());
                boolean covered = false;
                for (Dbm z : zones) {
                    if (n.state.zone().isSubsetOf(z)) {
                        covered = true;
                        break;
                    }
                }
                if (covered) {
                    continue;
                }
                zones.removeIf(z -> z.isSubsetOf(n.state.zone()));
                zones.add(n.state.zone());
                if (++explored > maxStates) {
                    return new CoverTime(CoverTime.Answer.UNKNOWN, -1, false, explored - 1);
                }
                graph.successors(n.state, (move, next) -> waiting.add(node(next, mask(set, next, n.mask), global)));
            }
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while searching for the shortest time to set every"
                    + " trap: " + e.format());
        }
        return new CoverTime(CoverTime.Answer.NONE, -1, false, explored);
    }

    private static long mask(List<StateProperty> traps, SymState s, long mask) {
        for (int t = 0; t < traps.size(); t++) {
            if ((mask & 1L << t) == 0 && traps.get(t).holdsSomewhere(s)) {
                mask |= 1L << t;
            }
        }
        return mask;
    }

    private static Node node(SymState s, long mask, int global) {
        int raw = s.zone().lowerBound(global);
        return new Node(s, mask, Bound.value(raw), Bound.isStrict(raw));
    }
}
