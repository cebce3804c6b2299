package io.dtron.engine.internal.sem;

import io.dtron.model.ClockVariable;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.Type;
import java.util.ArrayList;
import java.util.List;

/**
 * Not API. The largest constants each clock is compared with, split into lower bounds ({@code x > c}, {@code x >= c})
 * and upper bounds ({@code x < c}, {@code x <= c}, invariants), for Extra+_LU and Extra_M. Absent (null) when
 * a clock is compared with a non-constant expression or with another clock: those models are explored without
 * extrapolation.
 */
public final class ClockLimits {
    /** Per process, per location, per clock: the lower and upper limits from that location on. */
    private final int[][][] lower;
    private final int[][][] upper;
    /** Limits that hold everywhere: the queries' clock bounds. */
    private final int[] globalLower;
    private final int[] globalUpper;

    private ClockLimits(int[][][] lower, int[][][] upper, int[] globalLower, int[] globalUpper) {
        this.lower = lower;
        this.upper = upper;
        this.globalLower = globalLower;
        this.globalUpper = globalUpper;
    }

    /**
     * The limits of {@code network}'s guards and invariants plus {@code extra} atoms of the queries ({@code
     * {clock, constant, isLower}}), over {@code dimension} clocks (with the reference clock); null when
     * extrapolation would be unsound. The limits are local to locations (Behrmann,
     * Bouyer, Fleury, Larsen, "Static guard analysis in timed automata verification", 2003): a constant counts
     * in a location when a guard or invariant compares a clock with it on a path from there before the process
     * resets that clock; a state's limit is the largest over its processes' locations.
     */
    public static ClockLimits of(Network network, int dimension, List<int[]> extra) {
        int[] globalLower = new int[dimension];
        int[] globalUpper = new int[dimension];
        java.util.Arrays.fill(globalLower, -1);
        java.util.Arrays.fill(globalUpper, -1);
        for (int[] atom : extra) {
            int[] side = atom[2] != 0 ? globalLower : globalUpper;
            side[atom[0]] = Math.max(side[atom[0]], atom[1]);
        }
        int n = network.processes().size();
        int[][][] lower = new int[n][][];
        int[][][] upper = new int[n][][];
        for (Process p : network.processes()) {
            int locations = p.locations().size();
            int[][] lo = new int[locations][dimension];
            int[][] up = new int[locations][dimension];
            for (int l = 0; l < locations; l++) {
                java.util.Arrays.fill(lo[l], -1);
                java.util.Arrays.fill(up[l], -1);
                Location loc = p.locations().get(l);
                if (loc.invariant() != null && !collect(loc.invariant(), lo[l], up[l])) {
                    return null;
                }
            }
            List<boolean[]> resets = new ArrayList<>();
            for (Edge e : p.edges()) {
                if (e.guard() != null && !collect(e.guard(), lo[e.source()], up[e.source()])) {
                    return null;
                }
                boolean[] reset = new boolean[dimension];
                for (Expression u : e.updates()) {
                    if (!resets(u, reset)) {
                        return null;
                    }
                }
                resets.add(reset);
            }
            boolean changed = true;
            while (changed) {
                changed = false;
                for (int k = 0; k < p.edges().size(); k++) {
                    Edge e = p.edges().get(k);
                    boolean[] reset = resets.get(k);
                    for (int x = 1; x < dimension; x++) {
                        if (reset[x]) {
                            continue;
                        }
                        if (lo[e.target()][x] > lo[e.source()][x]) {
                            lo[e.source()][x] = lo[e.target()][x];
                            changed = true;
                        }
                        if (up[e.target()][x] > up[e.source()][x]) {
                            up[e.source()][x] = up[e.target()][x];
                            changed = true;
                        }
                    }
                }
            }
            lower[p.index()] = lo;
            upper[p.index()] = up;
        }
        return new ClockLimits(lower, upper, globalLower, globalUpper);
    }

    /** Fills the limits of the state {@code s} (its locations) into {@code lo} and {@code up}. */
    public void fill(SymState s, int[] lo, int[] up) {
        fill(s.locations(), lo, up);
    }

    /** Fills the limits of a state in {@code locations} into {@code lo} and {@code up}. */
    public void fill(int[] locations, int[] lo, int[] up) {
        System.arraycopy(globalLower, 0, lo, 0, lo.length);
        System.arraycopy(globalUpper, 0, up, 0, up.length);
        for (int p = 0; p < lower.length; p++) {
            int l = locations[p];
            if (l < 0) {
                continue;
            }
            int[] pl = lower[p][l];
            int[] pu = upper[p][l];
            for (int x = 1; x < lo.length; x++) {
                if (pl[x] > lo[x]) {
                    lo[x] = pl[x];
                }
                if (pu[x] > up[x]) {
                    up[x] = pu[x];
                }
            }
        }
    }

    /**
     * Records in {@code reset} the clocks an update sets to a constant; false for a clock assignment whose value
     * is another clock (extrapolation with these limits would then be unsound). Assignments inside functions are
     * not seen: such a clock just keeps its limits, which is sound.
     */
    private static boolean resets(Expression u, boolean[] reset) {
        if (u instanceof Expression.Assign a && (a.target().type() instanceof Type.Clock)) {
            if (a.value().type() instanceof Type.Clock) {
                return false;
            }
            if (a.target() instanceof Expression.ClockRef c && c.clock().type() instanceof Type.Clock) {
                reset[c.clock().index()] = true;
            }
            return true;
        }
        if (u instanceof Expression.Binary b) {
            return resets(b.left(), reset) && resets(b.right(), reset);
        }
        return true;
    }

    private static boolean collect(Expression e, int[] lower, int[] upper) {
        if (!(e.type() instanceof Type.ClockConstraint) || !(e instanceof Expression.Binary b)) {
            return true;
        }
        if (b.op() == Expression.Operator.AND) {
            return collect(b.left(), lower, upper) && collect(b.right(), lower, upper);
        }
        if (b.op() == Expression.Operator.OR) {
            return false;
        }
        boolean clockLeft = mentionsClock(b.left());
        boolean clockRight = mentionsClock(b.right());
        if (clockLeft && clockRight || b.left().type() instanceof Type.ClockDifference
                || b.right().type() instanceof Type.ClockDifference) {
            return false;
        }
        long[] constant = {0};
        List<Integer> clocks = new ArrayList<>();
        if (!walk(b.left(), constant, clocks) || !walk(b.right(), constant, clocks)) {
            return false;
        }
        boolean isLess = b.op() == Expression.Operator.LT || b.op() == Expression.Operator.LE;
        boolean isGreater = b.op() == Expression.Operator.GT || b.op() == Expression.Operator.GE;
        boolean upperBound = clockLeft ? isLess : isGreater;
        boolean lowerBound = clockLeft ? isGreater : isLess;
        if (!isLess && !isGreater) {
            upperBound = true;
            lowerBound = true;
        }
        if (constant[0] > io.dtron.engine.internal.zone.Bound.MAX_VALUE / 4) {
            return false;
        }
        int c = (int) constant[0];
        for (int x : clocks) {
            if (upperBound) {
                upper[x] = Math.max(upper[x], c);
            }
            if (lowerBound) {
                lower[x] = Math.max(lower[x], c);
            }
        }
        return true;
    }

    private static boolean mentionsClock(Expression e) {
        return e.type() instanceof Type.Clock || e.type() instanceof Type.ClockDifference
                || e instanceof Expression.Binary b && (mentionsClock(b.left()) || mentionsClock(b.right()));
    }

    /**
     * Walks one side of a clock constraint: adds the absolute values of its constants to {@code constant[0]} and its
     * clocks (every element of a clock array) to {@code clocks}; false for anything else (a variable, a product).
     */
    static boolean walk(Expression e, long[] constant, List<Integer> clocks) {
        if (e instanceof Expression.Constant c) {
            constant[0] += Math.abs((long) c.value());
            return true;
        }
        if (e instanceof Expression.ClockRef c) {
            ClockVariable v = c.clock();
            for (int i = v.index(); i < v.index() + v.type().clocks(); i++) {
                clocks.add(i);
            }
            return true;
        }
        if (e instanceof Expression.Index i && i.type() instanceof Type.Clock) {
            return walk(i.array(), constant, clocks);
        }
        if (e instanceof Expression.Binary b && (b.op() == Expression.Operator.ADD
                || b.op() == Expression.Operator.SUB)) {
            return walk(b.left(), constant, clocks) && walk(b.right(), constant, clocks);
        }
        return false;
    }
}
