package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.verify.VerifierOptions;
import io.dtron.model.Network;
import io.dtron.model.Process;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;

/**
 * What can be covered of a closed network: the locations and edges a search of its zone graph reaches (an edge is
 * reached when it takes part in a move from a reachable state), within a time and state budget. When the budget
 * runs out, {@link #stopped()} says so and nothing is known to be unreachable.
 */
public final class Coverable {
    private final boolean[][] locations;
    private final boolean[][] edges;
    private final String stopped;

    private Coverable(boolean[][] locations, boolean[][] edges, String stopped) {
        this.locations = locations;
        this.edges = edges;
        this.stopped = stopped;
    }

    /** Nothing checked: everything counts as coverable, for {@code reason}. */
    public static Coverable failed(Network network, String reason) {
        int n = network.processes().size();
        boolean[][] locations = new boolean[n][];
        boolean[][] edges = new boolean[n][];
        for (Process p : network.processes()) {
            locations[p.index()] = new boolean[p.locations().size()];
            edges[p.index()] = new boolean[p.edges().size()];
        }
        return new Coverable(locations, edges, reason);
    }

    /** No check asked for: everything counts as coverable. */
    public static Coverable unchecked(Network network) {
        return failed(network, "what can be covered was not checked");
    }

    /** The last search, for the same network (the same object) searched again with the same budget. */
    private static volatile Last last;

    private record Last(java.lang.ref.WeakReference<Network> network, Duration timeLimit, long maxStates,
                        Coverable result) {
    }

    /**
     * {@link #of}, or the answer of the last search when it was of this very network with the same budget: runs of
     * many seeds of one loaded model search once.
     */
    public static Coverable cached(Network network, Duration timeLimit, long maxStates) {
        Last l = last;
        if (l != null && l.network().get() == network && l.timeLimit().equals(timeLimit) && l.maxStates() == maxStates) {
            return l.result();
        }
        Coverable result = of(network, timeLimit, maxStates);
        last = new Last(new java.lang.ref.WeakReference<>(network), timeLimit, maxStates, result);
        return result;
    }

    /** Searches {@code network} for at most {@code timeLimit} and {@code maxStates} stored states. */
    public static Coverable of(Network network, Duration timeLimit, long maxStates) {
        int n = network.processes().size();
        boolean[][] locations = new boolean[n][];
        boolean[][] edges = new boolean[n][];
        for (Process p : network.processes()) {
            locations[p.index()] = new boolean[p.locations().size()];
            edges[p.index()] = new boolean[p.edges().size()];
        }
        Checker checker = new Checker(network, VerifierOptions.defaults().withTimeLimit(timeLimit));
        Budget budget = new Budget("what can be covered", timeLimit, 0, Duration.ofSeconds(5));
        try {
            ZoneGraph graph = checker.graph(false, List.of());
            Map<Integer, List<SymState>> passed = new HashMap<>();
            ArrayDeque<SymState> waiting = new ArrayDeque<>();
            SymState initial = graph.initial();
            mark(initial, locations);
            add(passed, initial);
            waiting.add(initial);
            long[] stored = {1};
            while (!waiting.isEmpty()) {
                SymState s = waiting.poll();
                budget.explore();
                graph.successors(s, (move, next) -> {
                    for (var step : move.steps()) {
                        edges[step.process()][step.edge().index()] = true;
                    }
                    if (add(passed, next)) {
                        mark(next, locations);
                        waiting.add(next);
                        stored[0]++;
                    }
                });
                if (stored[0] > maxStates) {
                    return new Coverable(locations, edges, "the check of what can be covered stopped at its budget of "
                            + maxStates + " stored states");
                }
            }
            return new Coverable(locations, edges, null);
        } catch (Budget.LimitReached e) {
            return new Coverable(locations, edges, "the check of what can be covered stopped at its budget of "
                    + timeLimit.toMillis() + " ms");
        }
    }

    private static void mark(SymState s, boolean[][] locations) {
        for (int p = 0; p < locations.length; p++) {
            if (s.location(p) >= 0) {
                locations[p][s.location(p)] = true;
            }
        }
    }

    /** Adds {@code s} unless a stored state of its discrete part includes it; false if it did. */
    private static boolean add(Map<Integer, List<SymState>> passed, SymState s) {
        List<SymState> group = passed.computeIfAbsent(s.discreteHash(), k -> new ArrayList<>(2));
        for (SymState o : group) {
            if (o.sameDiscrete(s) && s.zone().isSubsetOf(o.zone())) {
                return false;
            }
        }
        group.removeIf(o -> o.sameDiscrete(s) && o.zone().isSubsetOf(s.zone()));
        group.add(s);
        return true;
    }

    /** Whether location {@code l} of process {@code p} was reached (or the search stopped early). */
    public boolean location(int p, int l) {
        return stopped != null || locations[p][l];
    }

    /** Whether edge {@code e} of process {@code p} was reached (or the search stopped early). */
    public boolean edge(int p, int e) {
        return stopped != null || edges[p][e];
    }

    /** Whether location {@code l} of process {@code p} was reached by the search (proved reachable). */
    public boolean locationReached(int p, int l) {
        return locations[p][l];
    }

    /** Whether edge {@code e} of process {@code p} was reached by the search (proved reachable). */
    public boolean edgeReached(int p, int e) {
        return edges[p][e];
    }

    /** Null when the search was complete; else why it stopped. */
    public String stopped() {
        return stopped;
    }
}
