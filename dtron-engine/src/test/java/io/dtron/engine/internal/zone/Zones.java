package io.dtron.engine.internal.zone;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Random;
import java.util.function.Predicate;

/**
  * Test support: random zones, rational grid points and checks that do not rely on the code under
  * test. A point is a {@code long[]} of numerators over a denominator given separately; index 0 is
  * the reference clock and is always 0.
  */
final class Zones {

    private Zones() {}

    /** A constraint {@code x_i - x_j ⋈ value(raw)}. */
    record Constraint(int i, int j, int raw) {

        /** Checks the constraint on a rational point with exact integer arithmetic. */
        boolean holds(long[] v, long den) {
            return Zones.holds(v, den, i, j, raw);
        }

        @Override
        public String toString() {
            return "x" + i + "-x" + j + Bound.toString(raw);
        }
    }

    /** Exact semantic check of {@code v_i - v_j ⋈ value(raw)} for {@code v = num / den}. */
    static boolean holds(long[] v, long den, int i, int j, int raw) {
        if (raw == Bound.INFINITY) {
            return true;
        }
        long diff = v[i] - v[j];
        long limit = (long) (raw >> 1) * den;
        return (raw & 1) == 0 ? diff < limit : diff <= limit;
    }

    /** Returns a random constraint over the clocks of a zone of dimension {@code dim}. */
    static Constraint randomConstraint(Random r, int dim, int maxConst) {
        int i = r.nextInt(dim);
        int j = r.nextInt(dim - 1);
        if (j >= i) {
            j++;
        }
        int value;
        if (j == 0) {
            value = r.nextInt(maxConst + 1); // x_i <= c
        } else if (i == 0) {
            value = -r.nextInt(maxConst + 1); // x_j >= c
        } else {
            value = r.nextInt(2 * maxConst + 1) - maxConst; // x_i - x_j <= c
        }
        return new Constraint(i, j, Bound.of(value, r.nextBoolean()));
    }

    /** Applies one random operation with constants in {@code [0, maxConst]}. */
    static void randomOperation(Random r, Dbm z, int maxConst) {
        int dim = z.dimension();
        int x = 1 + r.nextInt(dim - 1);
        switch (r.nextInt(10)) {
            case 0, 1 -> z.up();
            case 2 -> z.reset(x, r.nextInt(maxConst + 1));
            case 3 -> z.free(x);
            case 4 -> z.copyClock(x, r.nextInt(dim));
            case 5 -> z.down();
            default -> {
                Constraint c = randomConstraint(r, dim, maxConst);
                z.constrain(c.i(), c.j(), c.raw());
            }
        }
    }

    /** Returns a random non-empty zone built from the zero or unconstrained zone by 1 to 8 operations. */
    static Dbm randomZone(Random r, int dim, int maxConst) {
        while (true) {
            Dbm z = r.nextBoolean() ? Dbm.zero(dim) : Dbm.unconstrained(dim);
            int steps = 1 + r.nextInt(8);
            for (int s = 0; s < steps; s++) {
                randomOperation(r, z, maxConst);
            }
            if (!z.isEmpty()) {
                return z;
            }
        }
    }

    /** Constrains every clock of {@code z} to at most {@code bound}, making it bounded. */
    static Dbm bounded(Dbm z, int bound) {
        for (int x = 1; x < z.dimension(); x++) {
            z.constrain(x, 0, Bound.le(bound));
        }
        return z;
    }

    /** Returns the largest absolute value of a finite entry of a non-empty zone. */
    static int maxConstant(Dbm z) {
        int max = 0;
        for (int i = 0; i < z.dimension(); i++) {
            for (int j = 0; j < z.dimension(); j++) {
                int b = z.upperBound(i, j);
                if (b != Bound.INFINITY) {
                    max = Math.max(max, Math.abs(Bound.value(b)));
                }
            }
        }
        return max;
    }

    /** Returns {@code z} with every constant multiplied by {@code factor}: the zone {@code factor * z}. */
    static Dbm scaled(Dbm z, int factor) {
        Dbm s = Dbm.unconstrained(z.dimension());
        for (int i = 0; i < z.dimension(); i++) {
            for (int j = 0; j < z.dimension(); j++) {
                int b = z.upperBound(i, j);
                if (i != j && b != Bound.INFINITY) {
                    s.constrain(i, j, Bound.of(Bound.value(b) * factor, Bound.isStrict(b)));
                }
            }
        }
        return s;
    }

    /**
      * Asserts that a non-empty zone's matrix is closed: zero diagonal, non-negative clocks and the
      * triangle inequality on every triple, with bound arithmetic done here on (value, strict) pairs.
      */
    static void assertCanonical(Dbm z) {
        int n = z.dimension();
        if (z.isEmpty()) {
            Dbm empty = Dbm.zero(n);
            empty.constrain(0, 0, Bound.LT_ZERO);
            assertEquals(empty, z, "empty zones have one representation");
            return;
        }
        for (int i = 0; i < n; i++) {
            assertEquals(Bound.LE_ZERO, z.upperBound(i, i), "diagonal of " + z);
            assertTrue(z.upperBound(0, i) <= Bound.LE_ZERO, "clocks non-negative in " + z);
            for (int j = 0; j < n; j++) {
                int ij = z.upperBound(i, j);
                for (int k = 0; k < n; k++) {
                    int ik = z.upperBound(i, k);
                    int kj = z.upperBound(k, j);
                    if (ik == Bound.INFINITY || kj == Bound.INFINITY) {
                        continue;
                    }
                    long sum = (long) Bound.value(ik) + Bound.value(kj);
                    boolean sumStrict = Bound.isStrict(ik) || Bound.isStrict(kj);
                    boolean tighter = ij != Bound.INFINITY
                            && (Bound.value(ij) < sum || Bound.value(ij) == sum && (Bound.isStrict(ij) || !sumStrict));
                    if (!tighter) {
                        fail("not closed at " + i + "," + j + " via " + k + ": " + Arrays.toString(matrix(z)));
                    }
                }
            }
        }
    }

    private static String[] matrix(Dbm z) {
        int n = z.dimension();
        String[] s = new String[n * n];
        for (int k = 0; k < s.length; k++) {
            s[k] = Bound.toString(z.upperBound(k / n, k % n));
        }
        return s;
    }

    /** Returns the point with the given numerators for clocks 1.. (the reference clock is added). */
    static long[] point(long... clocks) {
        long[] v = new long[clocks.length + 1];
        System.arraycopy(clocks, 0, v, 1, clocks.length);
        return v;
    }

    /**
      * Returns whether {@code test} holds for some point of the box {@code [lo[i], hi[i]]} of
      * numerators, trying them in order and stopping at the first; the array passed is reused.
      */
    static boolean anyPoint(long[] lo, long[] hi, Predicate<long[]> test) {
        int n = lo.length;
        for (int i = 1; i < n; i++) {
            if (lo[i] > hi[i]) {
                return false;
            }
        }
        long[] v = lo.clone();
        v[0] = 0;
        while (true) {
            if (test.test(v)) {
                return true;
            }
            int i = 1;
            while (i < n && v[i] == hi[i]) {
                v[i] = lo[i];
                i++;
            }
            if (i == n) {
                return false;
            }
            v[i]++;
        }
    }

    /**
      * Returns whether some point of the grid of multiples of {@code 1/(n+1)} (n clocks) inside the
      * clock bounds of the bounded zone {@code box} satisfies {@code test}. For a set that is a zone
      * with integer constants, or a difference of two such zones, inside {@code box}, this decides
      * non-emptiness exactly: such a set is a union of regions, and every region contains the point
      * whose k-th smallest distinct non-zero fractional part is k/(n+1).
      */
    static boolean existsGridPoint(Dbm box, Predicate<long[]> test) {
        int n = box.dimension();
        if (box.isEmpty()) {
            return false;
        }
        long den = gridDen(box);
        long[] lo = new long[n];
        long[] hi = new long[n];
        for (int x = 1; x < n; x++) {
            lo[x] = -Bound.value(box.upperBound(0, x)) * den;
            int up = box.upperBound(x, 0);
            if (up == Bound.INFINITY) {
                throw new IllegalArgumentException("zone not bounded: " + box);
            }
            hi[x] = Bound.value(up) * den;
        }
        return anyPoint(lo, hi, test);
    }

    /** The denominator {@code n+1} of the grid of {@link #existsGridPoint}. */
    static long gridDen(Dbm z) {
        return z.dimension();
    }

    /**
      * Returns sample points (numerators over {@code den}) with clocks in {@code [0, maxValue]}: the
      * whole grid when it has at most {@code count} points, otherwise {@code count} points mixing
      * uniform ones, points with integer values and equal or integer-spaced clocks, points found
      * inside {@code near} and their shifts by a common delay or single-clock nudges.
      */
    static List<long[]> points(Random r, Dbm near, long den, int maxValue, int count) {
        int n = near.dimension();
        long top = maxValue * den;
        List<long[]> out = new ArrayList<>();
        double gridSize = Math.pow(top + 1, n - 1);
        if (gridSize <= count) {
            long[] lo = new long[n];
            long[] hi = new long[n];
            Arrays.fill(hi, top);
            anyPoint(lo, hi, v -> !out.add(v.clone()));
            return out;
        }
        Dbm scaled = near.isEmpty() ? near : scaled(near, (int) den);
        while (out.size() < count) {
            long[] v;
            switch (r.nextInt(4)) {
                case 0 -> v = uniform(r, n, top);
                case 1 -> v = structured(r, n, den, top);
                case 2 -> v = inside(r, scaled, top);
                default -> v = nudged(r, inside(r, scaled, top), den, top);
            }
            if (v != null) {
                out.add(v);
            }
        }
        return out;
    }

    private static long[] uniform(Random r, int n, long top) {
        long[] v = new long[n];
        for (int x = 1; x < n; x++) {
            v[x] = (long) r.nextInt((int) top + 1);
        }
        return v;
    }

    private static long[] structured(Random r, int n, long den, long top) {
        long[] v = uniform(r, n, top);
        for (int x = 1; x < n; x++) {
            int kind = r.nextInt(3);
            if (kind == 0) {
                v[x] = den * r.nextInt((int) (top / den) + 1);
            } else if (kind == 1 && x > 1) {
                int y = 1 + r.nextInt(x - 1);
                v[x] = clamp(v[y] + den * (r.nextInt(5) - 2) + (r.nextInt(3) - 1), top);
            }
        }
        return v;
    }

    /** A grid point of the scaled zone found by fixing clocks one by one, or null. */
    private static long[] inside(Random r, Dbm scaled, long top) {
        if (scaled.isEmpty()) {
            return null;
        }
        int n = scaled.dimension();
        Dbm z = scaled.copy();
        long[] v = new long[n];
        int[] order = new int[n - 1];
        for (int k = 0; k < n - 1; k++) {
            order[k] = k + 1;
        }
        for (int k = n - 2; k > 0; k--) {
            int t = r.nextInt(k + 1);
            int tmp = order[k];
            order[k] = order[t];
            order[t] = tmp;
        }
        for (int x : order) {
            int lowB = z.upperBound(0, x);
            long lo = -Bound.value(lowB) + (Bound.isStrict(lowB) ? 1 : 0);
            int upB = z.upperBound(x, 0);
            long hi = upB == Bound.INFINITY ? top : Bound.value(upB) - (Bound.isStrict(upB) ? 1 : 0);
            hi = Math.min(hi, Math.max(lo, top));
            if (lo > hi) {
                return null;
            }
            v[x] = lo + (long) (r.nextDouble() * (hi - lo + 1));
            v[x] = Math.min(v[x], hi);
            if (!z.constrain(x, 0, Bound.le((int) v[x])) || !z.constrain(0, x, Bound.le((int) -v[x]))) {
                return null;
            }
        }
        return v;
    }

    private static long[] nudged(Random r, long[] v, long den, long top) {
        if (v == null) {
            return null;
        }
        int n = v.length;
        if (r.nextBoolean()) {
            long d = (r.nextInt(7) - 3) * (r.nextBoolean() ? den : 1);
            for (int x = 1; x < n; x++) {
                v[x] = clamp(v[x] + d, top);
            }
        } else {
            int x = 1 + r.nextInt(n - 1);
            v[x] = clamp(v[x] + (r.nextBoolean() ? 1 : -1) * (r.nextBoolean() ? den : 1), top);
        }
        return v;
    }

    private static long clamp(long value, long top) {
        return Math.max(0, Math.min(top, value));
    }
}
