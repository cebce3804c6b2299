package io.dtron.engine.internal.verify;

import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Process;
import io.dtron.model.Type;
import java.util.ArrayList;
import java.util.BitSet;
import java.util.List;

/**
 * A structural check for Zeno runs (Tripakis' strong non-Zenoness, per process): a cycle of a process's edges
 * takes time when, for some clock, one of its edges resets the clock and one has a guard {@code x > c} or
 * {@code x >= c} with {@code c > 0}. Every cycle of the network projects onto closed walks of its processes, so
 * when every cycle of every process takes time, so does every cycle of the network. A cycle that fails the
 * condition may still take time for other reasons (an invariant, data): it is reported as possibly Zeno.
 */
public final class ZenoCycles {
    private static final int MAX_CLOCKS = 10;

    private ZenoCycles() {
    }

    /** A cycle of {@code p} that may take no time, as its locations; null if every cycle takes time. */
    static List<String> possiblyZeno(Process p, int dimension) {
        return possiblyZeno(p, dimension, new BitSet());
    }

    /**
     * A cycle of {@code p} that it may go round on its own with no time passing (no edge of it receives on a
     * channel: sends and internal edges only), as its locations; null if there is none. For an environment process
     * whose sends are the inputs the system under test always accepts, such a cycle lets it give inputs without end
     * at one instant.
     */
    public static List<String> possiblyZenoAlone(Process p, int dimension) {
        BitSet receiving = new BitSet();
        for (int i = 0; i < p.edges().size(); i++) {
            Edge e = p.edges().get(i);
            if (e.sync() != null && e.sync().direction() == Edge.Direction.RECEIVE) {
                receiving.set(i);
            }
        }
        return possiblyZeno(p, dimension, receiving);
    }

    private static List<String> possiblyZeno(Process p, int dimension, BitSet excluded) {
        List<Edge> edges = p.edges();
        int n = edges.size();
        BitSet[] resets = new BitSet[dimension];
        BitSet[] lowerGuards = new BitSet[dimension];
        List<Integer> clocks = new ArrayList<>();
        for (int x = 1; x < dimension; x++) {
            resets[x] = new BitSet(n);
            lowerGuards[x] = new BitSet(n);
        }
        for (int i = 0; i < n; i++) {
            Edge e = edges.get(i);
            for (Expression u : e.updates()) {
                markResets(u, resets, i);
            }
            if (e.guard() != null) {
                markLowerGuards(e.guard(), lowerGuards, i);
            }
        }
        for (int x = 1; x < dimension; x++) {
            if (!resets[x].isEmpty() && !lowerGuards[x].isEmpty()) {
                clocks.add(x);
            }
        }
        if (clocks.size() > MAX_CLOCKS) {
            clocks = clocks.subList(0, MAX_CLOCKS);
        }
        // a cycle may take no time iff, for every clock, it avoids its resets or its lower guards
        for (int choice = 0; choice < 1 << clocks.size(); choice++) {
            BitSet removed = (BitSet) excluded.clone();
            for (int k = 0; k < clocks.size(); k++) {
                removed.or((choice >> k & 1) == 0 ? resets[clocks.get(k)] : lowerGuards[clocks.get(k)]);
            }
            List<String> cycle = cycle(p, removed);
            if (cycle != null) {
                return cycle;
            }
        }
        return null;
    }

    /**
     * A cycle of {@code p}'s edges not in {@code removed} with at least one edge that is not a receiving one, as
     * its locations, or null. (A process is driven around a cycle of receiving edges only by senders, whose own
     * cycles are checked.)
     */
    private static List<String> cycle(Process p, BitSet removed) {
        List<Edge> edges = p.edges();
        for (int i = 0; i < edges.size(); i++) {
            Edge first = edges.get(i);
            if (removed.get(i) || first.sync() != null && first.sync().direction() == Edge.Direction.RECEIVE) {
                continue;
            }
            // a path back from the edge's target to its source
            int locations = p.locations().size();
            int[] previous = new int[locations];
            java.util.Arrays.fill(previous, -2);
            java.util.ArrayDeque<Integer> queue = new java.util.ArrayDeque<>();
            previous[first.target()] = -1;
            queue.add(first.target());
            while (!queue.isEmpty() && previous[first.source()] == -2) {
                int l = queue.poll();
                for (int k = 0; k < edges.size(); k++) {
                    Edge e = edges.get(k);
                    if (e.source() == l && !removed.get(k) && previous[e.target()] == -2) {
                        previous[e.target()] = l;
                        queue.add(e.target());
                    }
                }
            }
            if (previous[first.source()] != -2) {
                List<String> cycle = new ArrayList<>();
                for (int l = first.source(); l != -1; l = previous[l]) {
                    cycle.add(0, p.locations().get(l).name());
                }
                cycle.add(0, p.locations().get(first.source()).name());
                return cycle;
            }
        }
        return null;
    }

    private static void markResets(Expression u, BitSet[] resets, int edge) {
        if (u instanceof Expression.Assign a && a.target() instanceof Expression.ClockRef c
                && c.clock().type() instanceof Type.Clock) {
            resets[c.clock().index()].set(edge);
        } else if (u instanceof Expression.Binary b) {
            markResets(b.left(), resets, edge);
            markResets(b.right(), resets, edge);
        }
    }

    private static void markLowerGuards(Expression g, BitSet[] lower, int edge) {
        if (!(g instanceof Expression.Binary b)) {
            return;
        }
        if (b.op() == Expression.Operator.AND) {
            markLowerGuards(b.left(), lower, edge);
            markLowerGuards(b.right(), lower, edge);
            return;
        }
        Expression clock;
        Expression bound;
        boolean lowerBound;
        if (b.left() instanceof Expression.ClockRef) {
            clock = b.left();
            bound = b.right();
            lowerBound = b.op() == Expression.Operator.GT || b.op() == Expression.Operator.GE
                    || b.op() == Expression.Operator.EQ;
        } else if (b.right() instanceof Expression.ClockRef) {
            clock = b.right();
            bound = b.left();
            lowerBound = b.op() == Expression.Operator.LT || b.op() == Expression.Operator.LE
                    || b.op() == Expression.Operator.EQ;
        } else {
            return;
        }
        boolean positive = bound instanceof Expression.Constant c && (c.value() > 0 || c.value() == 0
                && (b.op() == Expression.Operator.GT || b.op() == Expression.Operator.LT));
        Expression.ClockRef ref = (Expression.ClockRef) clock;
        if (lowerBound && positive && ref.clock().type() instanceof Type.Clock) {
            lower[ref.clock().index()].set(edge);
        }
    }
}
