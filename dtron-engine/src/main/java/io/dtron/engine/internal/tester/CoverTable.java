package io.dtron.engine.internal.tester;

import io.dtron.engine.internal.verify.DiscreteGraph;
import java.lang.ref.WeakReference;
import java.util.Arrays;
import java.util.BitSet;
import java.util.IdentityHashMap;
import java.util.Map;

/**
 * The coverage strategy's plan for covering every target left, not each on its own: for every subset of a few
 * targets (edges that an arc takes, goal nodes that an arc enters) and every node of the planner's graph, the fewest
 * moves from the node that cover the whole subset, where giving a target up costs the horizon plus one move (as
 * {@link Steerer}'s sum caps each distance). Built once per graph, targets and horizon (runs of many seeds, or of many
 * mutants, share it: it is read-only once built); after a target is covered the table of the smaller subset is already
 * in it.
 */
final class CoverTable {
    /** The most targets a table is built for. */
    static final int MAX_TARGETS = 12;

    /** The most entries (subsets times nodes) a table may have: 8 MB of ints. */
    static final long MAX_ENTRIES = 1L << 21;

    private final int[] edges;
    private final int[] goals;
    private final int penalty;
    /** Per subset (a bit mask: the edges from bit 0, then the goals), the moves from each node that cover it. */
    private final int[][] moves;
    /** Per arc of the graph (the graph's own arc objects): the targets it covers, as a mask. */
    private final Map<DiscreteGraph.Arc, Integer> arcMasks;

    private CoverTable(DiscreteGraph graph, int[] edges, int[] goals, int horizon) {
        this.edges = edges;
        this.goals = goals;
        this.penalty = horizon + 1;
        int nodes = graph.size();
        int arcCount = 0;
        for (int n = 0; n < nodes; n++) {
            arcCount += graph.arcs(n).length;
        }
        int[] source = new int[arcCount];
        int[] target = new int[arcCount];
        int[] mask = new int[arcCount];
        int[] intoCount = new int[nodes + 1];
        arcMasks = new IdentityHashMap<>();
        int k = 0;
        for (int n = 0; n < nodes; n++) {
            for (DiscreteGraph.Arc a : graph.arcs(n)) {
                source[k] = n;
                target[k] = a.target();
                mask[k] = maskOf(graph, a);
                arcMasks.put(a, mask[k]);
                intoCount[a.target() + 1]++;
                k++;
            }
        }
        // the arcs into each node, as one array with offsets
        for (int n = 0; n < nodes; n++) {
            intoCount[n + 1] += intoCount[n];
        }
        int[] into = new int[arcCount];
        int[] fill = Arrays.copyOf(intoCount, nodes);
        for (int a = 0; a < arcCount; a++) {
            into[fill[target[a]]++] = a;
        }
        int targets = edges.length + goals.length;
        moves = new int[1 << targets][];
        moves[0] = new int[nodes];
        int top = targets * penalty + 1;
        int[] bucketStart = new int[top + 2];
        int[] sorted = new int[nodes];
        int[] queue = new int[arcCount + nodes];
        for (int set = 1; set < moves.length; set++) {
            int[] d = new int[nodes];
            Arrays.fill(d, Integer.MAX_VALUE);
            for (int t = 0; t < targets; t++) {
                if ((set & 1 << t) != 0) {
                    int[] without = moves[set & ~(1 << t)];
                    for (int n = 0; n < nodes; n++) {
                        d[n] = Math.min(d[n], penalty + without[n]);
                    }
                }
            }
            for (int a = 0; a < arcCount; a++) {
                if ((mask[a] & set) != 0) {
                    d[source[a]] = Math.min(d[source[a]], 1 + moves[set & ~mask[a]][target[a]]);
                }
            }
            // unit moves from initial values: the nodes in order of their initial value (counting sort), merged with
            // the queue of relaxed ones, whose values never decrease
            Arrays.fill(bucketStart, 0);
            for (int n = 0; n < nodes; n++) {
                bucketStart[d[n] + 1]++;
            }
            for (int v = 0; v <= top; v++) {
                bucketStart[v + 1] += bucketStart[v];
            }
            for (int n = 0; n < nodes; n++) {
                sorted[bucketStart[d[n]]++] = n;
            }
            int[] initial = d.clone();
            int s = 0;
            int head = 0;
            int tail = 0;
            while (s < nodes || head < tail) {
                int n;
                int value;
                if (head < tail && (s >= nodes || d[queue[head]] <= initial[sorted[s]])) {
                    n = queue[head++];
                    value = d[n];
                } else {
                    n = sorted[s++];
                    value = initial[n];
                    if (value > d[n]) {
                        continue; // already reached through the queue with less
                    }
                }
                for (int i = intoCount[n]; i < intoCount[n + 1]; i++) {
                    int a = into[i];
                    if ((mask[a] & set) == 0 && value + 1 < d[source[a]]) {
                        d[source[a]] = value + 1;
                        queue[tail++] = source[a];
                    }
                }
            }
            moves[set] = d;
        }
    }

    private int maskOf(DiscreteGraph graph, DiscreteGraph.Arc a) {
        int m = 0;
        for (int t = 0; t < edges.length; t++) {
            for (int e : a.edges()) {
                if (e == edges[t]) {
                    m |= 1 << t;
                }
            }
        }
        for (int t = 0; t < goals.length; t++) {
            if (graph.goalAt(goals[t], a.target())) {
                m |= 1 << (edges.length + t);
            }
        }
        return m;
    }

    /** The last table built, for the same graph (the same object), targets and horizon. */
    private static Last last;

    private record Last(WeakReference<DiscreteGraph> graph, int[] edges, int[] goals, int horizon, CoverTable table) {
    }

    /**
     * The table for {@code edges} and {@code goals} (goal numbers of the graph) on {@code graph} within {@code
     * horizon}, or null when there are too many targets for one.
     */
    static CoverTable of(DiscreteGraph graph, BitSet edges, BitSet goals, int horizon) {
        int targets = edges.cardinality() + goals.cardinality();
        if (targets == 0 || targets > MAX_TARGETS || ((long) graph.size() << targets) > MAX_ENTRIES) {
            return null;
        }
        int[] e = edges.stream().toArray();
        int[] g = goals.stream().toArray();
        synchronized (CoverTable.class) {
            Last l = last;
            if (l != null && l.graph().get() == graph && Arrays.equals(l.edges(), e) && Arrays.equals(l.goals(), g)
                    && l.horizon() == horizon) {
                return l.table();
            }
            CoverTable table = new CoverTable(graph, e, g, horizon);
            last = new Last(new WeakReference<>(graph), e, g, horizon, table);
            return table;
        }
    }

    /**
     * The subset of this table's targets that are left, as its bit mask, or -1 when a target left is not one of
     * this table's.
     */
    int maskOf(BitSet edgesLeft, BitSet goalsLeft) {
        int m = 0;
        int found = 0;
        for (int t = 0; t < edges.length; t++) {
            if (edgesLeft.get(edges[t])) {
                m |= 1 << t;
                found++;
            }
        }
        for (int t = 0; t < goals.length; t++) {
            if (goalsLeft.get(goals[t])) {
                m |= 1 << (edges.length + t);
                found++;
            }
        }
        return found == edgesLeft.cardinality() + goalsLeft.cardinality() ? m : -1;
    }

    /**
     * The score of arc {@code a} when the targets {@code left} (a mask of {@link #maskOf}) are left: one move plus
     * the fewest that cover the rest from its target; {@link DiscreteGraph#UNREACHABLE} when the arc covers none
     * of them and every one is beyond the horizon from its target.
     */
    int score(DiscreteGraph.Arc a, int left) {
        Integer m = arcMasks.get(a);
        int covers = m == null ? 0 : m & left;
        int rest = left & ~covers;
        int d = moves[rest][a.target()];
        if (covers == 0 && d >= Integer.bitCount(rest) * penalty) {
            return DiscreteGraph.UNREACHABLE;
        }
        return 1 + d;
    }
}
