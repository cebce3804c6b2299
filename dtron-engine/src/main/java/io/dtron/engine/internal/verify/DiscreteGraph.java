package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.ClockLimits;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Network;
import io.dtron.model.Process;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.BitSet;
import java.util.HashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;

/**
 * The zone graph of a closed network projected on its discrete states (locations and variables): one node per
 * discrete state reached, one arc per move between them (its channel and the edges that take part), with the
 * goals ({@code E<>} queries) that hold somewhere in a node's zone. Built once, before a run, on the checker's zone
 * graph (Extra+_LU), keeping one zone per discrete state, the convex hull of the zones met there: an
 * over-approximation of the reachable states that ends after a few passes per discrete state, where the exact
 * search of a model of many independent clocks keeps thousands of zones each. A path of the zone graph is a path
 * here, so a node from which no goal node can be reached cannot reach the goal in the model either (when the
 * exploration was {@link #complete}); a path here need not be one of the zone graph, so distances are a guide,
 * not a promise.
 */
public final class DiscreteGraph {
    /** How long the exploration may take before it stops, incomplete: 5 s. */
    public static final long TIME_LIMIT_NANOS = 5_000_000_000L;

    /** Distance of a node from which a target cannot be reached. */
    public static final int UNREACHABLE = Integer.MAX_VALUE / 2;

    /** A move between two discrete states: its channel (-1 internal), its edges by global number, its target. */
    public record Arc(int channel, int[] edges, int target) {
        @Override
        public boolean equals(Object o) {
            return o instanceof Arc a && a.channel == channel && a.target == target && Arrays.equals(a.edges, edges);
        }

        @Override
        public int hashCode() {
            return 31 * (31 * channel + target) + Arrays.hashCode(edges);
        }
    }

    /** A discrete state as a hash key. */
    private record Key(SymState state) {
        @Override
        public boolean equals(Object o) {
            return o instanceof Key k && k.state.sameDiscrete(state);
        }

        @Override
        public int hashCode() {
            return state.discreteHash();
        }
    }

    private final Map<Key, Integer> ids = new HashMap<>();
    private final List<SymState> nodes = new ArrayList<>();
    private final List<Arc[]> arcs = new ArrayList<>();
    private final int[] edgeOffset;
    private final BitSet[] goalNodes;
    private final boolean complete;
    private final long zoneStates;
    /** Per node, its predecessors: built with the graph, which is read-only from then on (runs share it). */
    private final int[][] reverse;

    private DiscreteGraph(Network network, int goals, int maxStates, ZoneGraph graph, List<Property> properties) {
        this.edgeOffset = new int[network.processes().size()];
        int offset = 0;
        for (Process p : network.processes()) {
            edgeOffset[p.index()] = offset;
            offset += p.edges().size();
        }
        this.goalNodes = new BitSet[goals];
        for (int g = 0; g < goals; g++) {
            goalNodes[g] = new BitSet();
        }
        Map<Key, Dbm> passed = new HashMap<>();
        List<Set<Arc>> out = new ArrayList<>();
        ArrayDeque<SymState> waiting = new ArrayDeque<>();
        SymState init = graph.initial();
        waiting.add(init);
        passed.put(new Key(init), init.zone().copy());
        long visited = 0;
        boolean done = true;
        Property.StateInfo info = graph::deadlocked;
        long start = System.nanoTime();
        while (!waiting.isEmpty()) {
            if (++visited > maxStates || (visited & 1023) == 0 && System.nanoTime() - start > TIME_LIMIT_NANOS) {
                done = false;
                break;
            }
            SymState s = waiting.poll();
            int from = node(s, out);
            for (int g = 0; g < goals; g++) {
                if (!goalNodes[g].get(from)) {
                    List<Dbm> parts = new ArrayList<>();
                    properties.get(g).restrict(s, s.zone(), info, parts);
                    if (!parts.isEmpty()) {
                        goalNodes[g].set(from);
                    }
                }
            }
            graph.successors(s, (move, next) -> {
                int to = node(next, out);
                out.get(from).add(new Arc(move.channel(), edgesOf(move), to));
                Key key = new Key(next);
                Dbm hull = passed.get(key);
                if (hull != null && next.zone().isSubsetOf(hull)) {
                    return;
                }
                Dbm grown = hull == null ? next.zone().copy() : hull(hull, next.zone());
                passed.put(key, grown);
                waiting.add(next.withZone(grown.copy()));
            });
        }
        for (Set<Arc> a : out) {
            arcs.add(a.toArray(new Arc[0]));
        }
        this.complete = done;
        this.zoneStates = visited;
        this.reverse = reverse(nodes.size(), arcs);
    }

    /** The smallest zone holding {@code a} and {@code b} (both canonical): the weaker of their bounds. */
    private static Dbm hull(Dbm a, Dbm b) {
        int n = a.dimension();
        Dbm h = Dbm.unconstrained(n);
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < n; j++) {
                int bound = Math.max(a.upperBound(i, j), b.upperBound(i, j));
                if (i != j && bound != io.dtron.engine.internal.zone.Bound.INFINITY) {
                    h.constrain(i, j, bound);
                }
            }
        }
        return h;
    }

    /**
     * Explores {@code network} (at most {@code maxStates} symbolic states, for at most {@link #TIME_LIMIT_NANOS})
     * and marks where {@code goals} hold;
     * each must be an {@code E<>} query.
     *
     * @throws QueryException when a goal is not an {@code E<>} query or its property does not compile
     * @throws io.dtron.engine.UnsupportedModelException on a model error met during the exploration
     */
    public static DiscreteGraph explore(Network network, List<Query> goals, int maxStates) {
        PropertyCompiler compiler = new PropertyCompiler(network);
        List<Property> properties = new ArrayList<>();
        List<int[]> atoms = new ArrayList<>();
        boolean exact = true;
        boolean deadlock = false;
        for (Query q : goals) {
            Property p = compile(compiler, q);
            exact &= p.clockAtoms(atoms);
            deadlock |= p.mentionsDeadlock();
            properties.add(p);
        }
        Semantics semantics = new Semantics(network, 1, false);
        ClockLimits limits = exact ? ClockLimits.of(network, semantics.dimension(), atoms) : null;
        try {
            return new DiscreteGraph(network, goals.size(), maxStates, new ZoneGraph(semantics, limits, deadlock),
                    properties);
        } catch (ModelRuntimeException e) {
            throw new io.dtron.engine.UnsupportedModelException("model error while exploring the model for the"
                    + " planner: " + e.format());
        }
    }

    /** The last exploration, for the same network (the same object) explored again toward the same goals. */
    private static Last last;

    private record Last(java.lang.ref.WeakReference<Network> network, List<String> goals, int maxStates,
                        DiscreteGraph graph) {
    }

    /**
     * {@link #explore}, or the graph of the last exploration when it was of this very network toward the same goals
     * and bound: the runs of many seeds, or of many mutants tested against one model, explore it once. The graph is
     * read-only once built, so runs on many threads share it.
     */
    public static DiscreteGraph cached(Network network, List<Query> goals, int maxStates) {
        List<String> texts = goals.stream().map(Query::text).toList();
        synchronized (DiscreteGraph.class) {
            Last l = last;
            if (l != null && l.network().get() == network && l.goals().equals(texts) && l.maxStates() == maxStates) {
                return l.graph();
            }
            DiscreteGraph graph = explore(network, goals, maxStates);
            last = new Last(new java.lang.ref.WeakReference<>(network), texts, maxStates, graph);
            return graph;
        }
    }

    static Property compile(PropertyCompiler compiler, Query q) {
        if (q.kind() == Query.Kind.INVALID) {
            throw new QueryException(q.reason());
        }
        if (q.kind() != Query.Kind.EXISTS_EVENTUALLY) {
            throw new QueryException("goal '" + q.text() + "' is not a reachability query: a goal is written"
                    + " E<> p");
        }
        return compiler.compile(q.text(), q.property(), q.column(), false);
    }

    private int node(SymState s, List<Set<Arc>> out) {
        Integer id = ids.get(new Key(s));
        if (id != null) {
            return id;
        }
        int n = nodes.size();
        SymState discrete = s.withZone(null);
        ids.put(new Key(discrete), n);
        nodes.add(discrete);
        out.add(new LinkedHashSet<>());
        return n;
    }

    /** The global numbers of the edges of {@code move}, sorted. */
    public int[] edgesOf(Semantics.Move move) {
        int[] e = new int[move.steps().size()];
        for (int i = 0; i < e.length; i++) {
            Semantics.Step step = move.steps().get(i);
            e[i] = edgeOffset[step.process()] + step.edge().index();
        }
        Arrays.sort(e);
        return e;
    }

    /** The global number of edge {@code edge} of process {@code process}. */
    public int edge(int process, int edge) {
        return edgeOffset[process] + edge;
    }

    /** The process of global edge number {@code edge}. */
    public int processOf(int edge) {
        int p = Arrays.binarySearch(edgeOffset, edge);
        if (p < 0) {
            return -p - 2;
        }
        while (p + 1 < edgeOffset.length && edgeOffset[p + 1] == edge) {
            p++; // processes without edges share an offset with the next
        }
        return p;
    }

    /** The node of {@code s}'s discrete part, or -1 when the exploration did not meet it. */
    public int node(SymState s) {
        Integer id = ids.get(new Key(s));
        return id == null ? -1 : id;
    }

    /** How many nodes there are. */
    public int size() {
        return nodes.size();
    }

    /** The arcs leaving node {@code n}. */
    public Arc[] arcs(int n) {
        return arcs.get(n);
    }

    /** Whether goal {@code g} holds somewhere in node {@code n}. */
    public boolean goalAt(int g, int n) {
        return goalNodes[g].get(n);
    }

    /** The nodes where goal {@code g} holds somewhere. */
    public BitSet goalNodes(int g) {
        return (BitSet) goalNodes[g].clone();
    }

    /** Whether every reachable symbolic state was explored: then unreachability is proved. */
    public boolean complete() {
        return complete;
    }

    /** How many symbolic states the exploration visited. */
    public long zoneStates() {
        return zoneStates;
    }

    /**
     * For every node, the fewest arcs to a node of {@code targets} (0 in one), counting an arc that {@code
     * arcTarget} accepts as reaching the target; {@link #UNREACHABLE} when none can be reached.
     */
    public int[] distances(BitSet targets, java.util.function.Predicate<Arc> arcTarget) {
        int[][] rev = reverse;
        int[] dist = new int[nodes.size()];
        Arrays.fill(dist, UNREACHABLE);
        ArrayDeque<Integer> queue = new ArrayDeque<>();
        for (int n = 0; n < dist.length; n++) {
            if (targets.get(n)) {
                dist[n] = 0;
                queue.add(n);
            }
        }
        if (arcTarget != null) {
            for (int n = 0; n < dist.length; n++) {
                if (dist[n] != 0) {
                    for (Arc a : arcs.get(n)) {
                        if (arcTarget.test(a)) {
                            dist[n] = 1;
                            break;
                        }
                    }
                }
            }
            // breadth-first from distance 1 needs the 0s first: a bucket queue of two levels
            for (int n = 0; n < dist.length; n++) {
                if (dist[n] == 1) {
                    queue.add(n);
                }
            }
        }
        while (!queue.isEmpty()) {
            int n = queue.poll();
            for (int p : rev[n]) {
                if (dist[p] > dist[n] + 1) {
                    dist[p] = dist[n] + 1;
                    queue.add(p);
                }
            }
        }
        return dist;
    }

    private static int[][] reverse(int size, List<Arc[]> arcs) {
        List<List<Integer>> rev = new ArrayList<>();
        for (int n = 0; n < size; n++) {
            rev.add(new ArrayList<>());
        }
        for (int n = 0; n < size; n++) {
            for (Arc a : arcs.get(n)) {
                rev.get(a.target()).add(n);
            }
        }
        int[][] reverse = new int[size][];
        for (int n = 0; n < size; n++) {
            reverse[n] = rev.get(n).stream().mapToInt(Integer::intValue).distinct().toArray();
        }
        return reverse;
    }
}
