package io.dtron.engine.internal.zone;

import static io.dtron.engine.internal.zone.Bound.INFINITY;
import static io.dtron.engine.internal.zone.Bound.LE_ZERO;
import static io.dtron.engine.internal.zone.Bound.LT_ZERO;

import java.util.Arrays;
import java.util.Objects;

/**
  * A zone: a convex set of clock valuations described by a difference bound matrix, always kept
  * in canonical (shortest-path closed) form.
  *
  * <p>Clocks are indexed {@code 1..dimension()-1}; index 0 is the reference clock, constantly 0.
  * Entry {@code (i, j)} is the tightest raw {@link Bound} on {@code x_i - x_j}, so {@code (i, 0)}
  * bounds {@code x_i} from above and {@code (0, i)} bounds {@code -x_i}. All valuations are
  * non-negative. Because the form is canonical, two zones are {@link #equals equal} exactly when
  * they hold the same valuations; all empty zones of a dimension are equal.
  *
  * <p>Zones are mutable and not thread-safe; operations work in place on a flat row-major {@code
  * int[]} and, except {@link #copy} and {@code toString}, allocate nothing. Mutating a zone changes
  * its {@link #hashCode}. Extrapolation implements Extra_M ({@link #extrapolateMaxBounds}) and
  * Extra+_LU ({@link #extrapolateLU}).
  *
  * <p>Bound values are integers (engine ticks). Results are exact while every bound derived by
  * closure stays within {@code ±Bound.MAX_VALUE}; beyond that range constraints are only ever
  * weakened, never wrapped (see {@link Bound}).
  */
public final class Dbm {

    /** The smallest finite raw bound ({@code < -Bound.MAX_VALUE}); sums below it are clamped to it. */
    private static final int MIN_RAW = Bound.lt(-Bound.MAX_VALUE);

    private final int dim;
    private final int[] m;

    private Dbm(int dim) {
        if (dim < 1) {
            throw new IllegalArgumentException("dimension must be at least 1: " + dim);
        }
        this.dim = dim;
        this.m = new int[dim * dim];
    }

    /** Returns the zone where every clock is 0; {@code dimension} counts the reference clock. */
    public static Dbm zero(int dimension) {
        Dbm z = new Dbm(dimension);
        Arrays.fill(z.m, LE_ZERO);
        return z;
    }

    /** Returns the zone of all non-negative valuations; {@code dimension} counts the reference. */
    public static Dbm unconstrained(int dimension) {
        Dbm z = new Dbm(dimension);
        int[] d = z.m;
        Arrays.fill(d, INFINITY);
        for (int j = 0; j < dimension; j++) {
            d[j] = LE_ZERO;
            d[j * dimension + j] = LE_ZERO;
        }
        return z;
    }

    /** Returns the number of clocks plus one (for the reference clock). */
    public int dimension() {
        return dim;
    }

    /** Returns an independent copy of this zone. */
    public Dbm copy() {
        Dbm z = new Dbm(dim);
        System.arraycopy(m, 0, z.m, 0, m.length);
        return z;
    }

    /**
      * Overwrites this zone with {@code other}, without allocating.
      *
      * @throws IllegalArgumentException if the dimensions differ
      */
    public void copyFrom(Dbm other) {
        checkSameDimension(other);
        System.arraycopy(other.m, 0, m, 0, m.length);
    }

    /** Returns whether the zone holds no valuation. */
    public boolean isEmpty() {
        return m[0] < LE_ZERO;
    }

    /**
      * Returns the tightest raw bound {@code b} with {@code x_i - x_j ⋈ value(b)} for every
      * valuation of the zone, or {@link Bound#INFINITY} if there is none. Meaningless for an empty
      * zone.
      */
    public int upperBound(int i, int j) {
        return m[Objects.checkIndex(i, dim) * dim + Objects.checkIndex(j, dim)];
    }

    /**
      * Returns the tightest lower bound of {@code x_i - x_j} encoded as a raw bound {@code b}: every
      * valuation has {@code x_i - x_j > value(b)} if {@code b} is strict, {@code >= value(b)}
      * otherwise; {@link Bound#INFINITY} if {@code x_i - x_j} is unbounded below. Meaningless for an
      * empty zone.
      */
    public int lowerBound(int i, int j) {
        int b = upperBound(j, i);
        return b == INFINITY ? INFINITY : Bound.of(-Bound.value(b), Bound.isStrict(b));
    }

    /** Returns {@link #upperBound(int, int) upperBound(x, 0)}: the upper bound of clock {@code x}. */
    public int upperBound(int x) {
        return upperBound(x, 0);
    }

    /**
      * Returns {@link #lowerBound(int, int) lowerBound(x, 0)}: the lower bound of clock {@code x}, in
      * the encoding of {@link #lowerBound(int, int)}; never infinite.
      */
    public int lowerBound(int x) {
        return lowerBound(x, 0);
    }

    /**
      * Returns whether the zone holds the valuation {@code x_i = numerators[i] / denominator}.
      * {@code numerators[0]} (the reference clock) is not read.
      *
      * @throws IllegalArgumentException if {@code numerators.length != dimension()} or {@code
      *     denominator <= 0}
      * @throws ArithmeticException if a bound times {@code denominator} overflows a {@code long}
      */
    public boolean contains(long[] numerators, long denominator) {
        if (numerators.length != dim || denominator <= 0) {
            throw new IllegalArgumentException("need " + dim + " numerators and a positive denominator");
        }
        if (isEmpty()) {
            return false;
        }
        for (int i = 0; i < dim; i++) {
            long vi = i == 0 ? 0 : numerators[i];
            for (int j = 0; j < dim; j++) {
                int b = m[i * dim + j];
                if (i == j || b == INFINITY) {
                    continue;
                }
                long diff = Math.subtractExact(vi, j == 0 ? 0 : numerators[j]);
                long limit = Math.multiplyExact((long) (b >> 1), denominator);
                if (Bound.isStrict(b) ? diff >= limit : diff > limit) {
                    return false;
                }
            }
        }
        return true;
    }

    /** Returns whether some valuation of the zone satisfies {@code x_i - x_j ⋈ value(bound)}. */
    public boolean satisfies(int i, int j, int bound) {
        int back = upperBound(j, i);
        return !isEmpty() && Bound.add(back, bound) >= LE_ZERO;
    }

    /**
      * Returns whether every valuation of this zone is in {@code other}.
      *
      * @throws IllegalArgumentException if the dimensions differ
      */
    public boolean isSubsetOf(Dbm other) {
        checkSameDimension(other);
        if (isEmpty()) {
            return true;
        }
        if (other.isEmpty()) {
            return false;
        }
        int[] o = other.m;
        for (int k = 0; k < m.length; k++) {
            if (m[k] > o[k]) {
                return false;
            }
        }
        return true;
    }

    /**
      * Returns the canonical matrix as {@code short}s, for storing many zones compactly: each raw bound as is,
      * {@link Bound#INFINITY} as {@link Short#MAX_VALUE}; null when a finite raw bound does not fit in a short
      * (constants beyond about ±16,000). The order of raw bounds is kept, so inclusion can be decided on the
      * packed form ({@link #isSubsetOf(short[])}, {@link #includes(short[])}).
      */
    public short[] pack() {
        short[] out = new short[m.length];
        for (int k = 0; k < m.length; k++) {
            int b = m[k];
            if (b == INFINITY) {
                out[k] = Short.MAX_VALUE;
            } else if (b >= Short.MAX_VALUE || b < Short.MIN_VALUE) {
                return null;
            } else {
                out[k] = (short) b;
            }
        }
        return out;
    }

    /**
      * Returns the zone that {@link #pack()} packed.
      *
      * @throws IllegalArgumentException if {@code packed.length != dimension * dimension}
      */
    public static Dbm unpack(int dimension, short[] packed) {
        Dbm z = new Dbm(dimension);
        if (packed.length != z.m.length) {
            throw new IllegalArgumentException("need " + z.m.length + " bounds, got " + packed.length);
        }
        for (int k = 0; k < packed.length; k++) {
            z.m[k] = packed[k] == Short.MAX_VALUE ? INFINITY : packed[k];
        }
        return z;
    }

    /**
      * Returns whether every valuation of this zone is in the packed zone {@code other} (see {@link #pack()}),
      * of the same dimension and not empty.
      */
    public boolean isSubsetOf(short[] other) {
        if (isEmpty()) {
            return true;
        }
        for (int k = 0; k < m.length; k++) {
            int o = other[k] == Short.MAX_VALUE ? INFINITY : other[k];
            if (m[k] > o) {
                return false;
            }
        }
        return true;
    }

    /**
      * Returns whether every valuation of the packed zone {@code other} (see {@link #pack()}), of the same
      * dimension and not empty, is in this zone.
      */
    public boolean includes(short[] other) {
        if (isEmpty()) {
            return false;
        }
        for (int k = 0; k < m.length; k++) {
            int o = other[k] == Short.MAX_VALUE ? INFINITY : other[k];
            if (o > m[k]) {
                return false;
            }
        }
        return true;
    }

    /**
      * Returns how this zone relates to {@code other} as sets of valuations.
      *
      * @throws IllegalArgumentException if the dimensions differ
      */
    public Relation relation(Dbm other) {
        checkSameDimension(other);
        boolean thisEmpty = isEmpty();
        boolean otherEmpty = other.isEmpty();
        if (thisEmpty || otherEmpty) {
            return thisEmpty && otherEmpty
                    ? Relation.EQUAL
                    : thisEmpty ? Relation.SUBSET : Relation.SUPERSET;
        }
        int[] o = other.m;
        boolean subset = true;
        boolean superset = true;
        for (int k = 0; k < m.length; k++) {
            if (m[k] > o[k]) {
                subset = false;
            } else if (m[k] < o[k]) {
                superset = false;
            }
            if (!subset && !superset) {
                return Relation.DIFFERENT;
            }
        }
        return subset ? (superset ? Relation.EQUAL : Relation.SUBSET) : Relation.SUPERSET;
    }

    /** Lets time pass: the zone becomes all {@code v + d} with {@code v} in it and {@code d >= 0}. */
    public void up() {
        if (isEmpty()) {
            return;
        }
        for (int i = 1; i < dim; i++) {
            m[i * dim] = INFINITY;
        }
    }

    /**
      * Goes back in time: the zone becomes all non-negative valuations {@code v - d} with {@code v}
      * in it and {@code d >= 0}.
      */
    public void down() {
        if (isEmpty()) {
            return;
        }
        for (int j = 1; j < dim; j++) {
            int b = LE_ZERO;
            for (int i = 1; i < dim; i++) {
                b = Math.min(b, m[i * dim + j]);
            }
            m[j] = b;
        }
    }

    /**
      * Intersects the zone with the constraint {@code x_i - x_j ⋈ value(bound)}, in time O(n^2).
      *
      * @return whether the zone is non-empty afterwards
      */
    public boolean constrain(int i, int j, int bound) {
        int ij = Objects.checkIndex(i, dim) * dim + Objects.checkIndex(j, dim);
        if (isEmpty()) {
            return false;
        }
        if (bound >= m[ij]) {
            return true;
        }
        if (Bound.add(bound, m[j * dim + i]) < LE_ZERO) {
            makeEmpty();
            return false;
        }
        m[ij] = bound;
        // The old matrix was closed and the new edge closes no negative cycle, so a shortest path
        // uses the new edge at most once: relax every pair k, l through k -> i -> j -> l.
        int rowJ = j * dim;
        int[] d = m;
        for (int k = 0; k < dim; k++) {
            int rowK = k * dim;
            int toJ = Bound.add(d[rowK + i], bound);
            if (toJ == INFINITY) {
                continue;
            }
            for (int l = 0; l < dim; l++) {
                int jl = d[rowJ + l];
                // Bound.add inlined (for finite bounds only the lower clamp can apply to a tighter sum), without
                // branches: whether a sum is tighter is hard to predict
                long sum = jl == INFINITY ? Long.MAX_VALUE : (long) toJ + jl - ((toJ | jl) & 1);
                d[rowK + l] = (int) Math.min(d[rowK + l], Math.max(sum, MIN_RAW));
            }
        }
        return true;
    }

    /**
      * Intersects the zone with every constraint {@code x_i - x_j ⋈ value(b)} listed as triples {@code i, j, b}
      * in {@code constraints}: the same zone as {@link #constrain} of each in turn. The upper bounds of single
      * clocks ({@code j} is 0), as invariants give them, are added together: a shortest path uses at most one of
      * them (it passes the reference clock at most once), so one pass through the reference clock closes the
      * matrix, in O(n^2) for all of them instead of O(n^2) each.
      *
      * @return whether the zone is non-empty afterwards
      */
    public boolean constrainAll(int[] constraints) {
        return constrainAll(constraints, constraints.length);
    }

    /** {@link #constrainAll(int[])} of the first {@code length} entries of {@code constraints}. */
    public boolean constrainAll(int[] constraints, int length) {
        if (isEmpty()) {
            return false;
        }
        int[] d = m;
        int n = dim;
        boolean tighter = false;
        for (int k = 0; k + 2 < length; k += 3) {
            int i = constraints[k];
            int b = constraints[k + 2];
            if (constraints[k + 1] != 0 || i == 0 || b >= d[Objects.checkIndex(i, n) * n]) {
                continue;
            }
            if (Bound.add(b, d[i]) < LE_ZERO) {
                makeEmpty();
                return false;
            }
            tighter = true;
        }
        if (tighter) {
            // column 0: the shortest path from each clock p to the reference through one new bound x_k <= b
            int[] toZero = new int[n];
            for (int p = 0; p < n; p++) {
                toZero[p] = d[p * n];
            }
            for (int k = 0; k + 2 < length; k += 3) {
                int i = constraints[k];
                int b = constraints[k + 2];
                if (constraints[k + 1] != 0 || i == 0 || b >= d[i * n]) {
                    // a bound the zone already has shortens no path
                    continue;
                }
                for (int p = 1; p < n; p++) {
                    int pi = d[p * n + i];
                    // Bound.add inlined: b is finite; only the lower clamp can apply to a tighter sum
                    long via = pi == INFINITY ? Long.MAX_VALUE : (long) pi + b - ((pi | b) & 1);
                    toZero[p] = (int) Math.min(toZero[p], Math.max(via, MIN_RAW));
                }
            }
            // Every new shortest path p -> q is p -> ... -> 0 -> ... -> q; row 0 itself is unchanged.
            for (int p = 1; p < n; p++) {
                int p0 = toZero[p];
                int rowP = p * n;
                if (p0 >= d[rowP]) {
                    continue;
                }
                d[rowP] = p0;
                for (int q = 1; q < n; q++) {
                    int zq = d[q];
                    if (q == p || zq == INFINITY) {
                        continue;
                    }
                    // Bound.add inlined: both finite, so only the lower clamp can apply to a tighter sum
                    long sum = (long) p0 + zq - ((p0 | zq) & 1);
                    if (sum < d[rowP + q]) {
                        d[rowP + q] = sum < MIN_RAW ? MIN_RAW : (int) sum;
                    }
                }
            }
        }
        for (int k = 0; k + 2 < length; k += 3) {
            int i = constraints[k];
            int j = constraints[k + 1];
            if ((j != 0 || i == 0) && !constrain(i, j, constraints[k + 2])) {
                return false;
            }
        }
        return true;
    }

    /**
      * Intersects this zone with {@code other}.
      *
      * @return whether this zone is non-empty afterwards
      * @throws IllegalArgumentException if the dimensions differ
      */
    public boolean intersect(Dbm other) {
        checkSameDimension(other);
        if (isEmpty()) {
            return false;
        }
        if (other.isEmpty()) {
            makeEmpty();
            return false;
        }
        int[] o = other.m;
        int tighter = 0;
        for (int k = 0; k < m.length; k++) {
            if (o[k] < m[k]) {
                tighter++;
            }
        }
        if (tighter <= dim) {
            // Few new constraints: add them one by one, O(n^2) each.
            for (int k = 0; k < m.length; k++) {
                if (o[k] < m[k] && !constrain(k / dim, k % dim, o[k])) {
                    return false;
                }
            }
            return true;
        }
        for (int k = 0; k < m.length; k++) {
            m[k] = Math.min(m[k], o[k]);
        }
        return close();
    }

    /**
      * Assigns the constant {@code value} to clock {@code x} (a reset when {@code value} is 0).
      *
      * @throws IllegalArgumentException if {@code value} is negative or above {@link
      *     Bound#MAX_VALUE}
      */
    public void reset(int x, int value) {
        checkClock(x);
        if (value < 0) {
            throw new IllegalArgumentException("clock value must be non-negative: " + value);
        }
        int upper = Bound.le(value);
        int lower = Bound.le(-value);
        if (isEmpty()) {
            return;
        }
        int rowX = x * dim;
        for (int j = 0; j < dim; j++) {
            if (j != x) {
                m[rowX + j] = Bound.add(upper, m[j]);
                m[j * dim + x] = Bound.add(m[j * dim], lower);
            }
        }
    }

    /**
     * Sets clock {@code x} back by {@code by} ({@code x := x - by}) in every valuation, keeping its distances to the
     * other clocks: exact, and the zone stays closed. Every valuation must have {@code x >= by}.
     */
    public void shift(int x, int by) {
        checkClock(x);
        if (isEmpty() || by == 0) {
            return;
        }
        if (by < 0 || Bound.compare(m[x], Bound.le(-by)) > 0) {
            throw new IllegalArgumentException("clock " + x + " is not at least " + by + " in " + this);
        }
        int less = Bound.le(-by);
        int more = Bound.le(by);
        int rowX = x * dim;
        for (int j = 0; j < dim; j++) {
            if (j != x) {
                m[rowX + j] = Bound.add(m[rowX + j], less);
                m[j * dim + x] = Bound.add(m[j * dim + x], more);
            }
        }
    }

    /** Removes every constraint on clock {@code x} except {@code x >= 0}. */
    public void free(int x) {
        checkClock(x);
        if (isEmpty()) {
            return;
        }
        int rowX = x * dim;
        for (int j = 0; j < dim; j++) {
            if (j != x) {
                m[rowX + j] = INFINITY;
                m[j * dim + x] = m[j * dim];
            }
        }
    }

    /** Assigns clock {@code y} to clock {@code x} ({@code x := y}); {@code y} may be 0. */
    public void copyClock(int x, int y) {
        checkClock(x);
        Objects.checkIndex(y, dim);
        if (x == y || isEmpty()) {
            return;
        }
        int rowX = x * dim;
        int rowY = y * dim;
        for (int j = 0; j < dim; j++) {
            if (j != x) {
                m[rowX + j] = m[rowY + j];
                m[j * dim + x] = m[j * dim + y];
            }
        }
    }

    /**
      * Extrapolates the zone with maximal constants: the operator Extra_M of Behrmann, Bouyer,
      * Larsen and Pelánek, "Lower and upper bounds in zone-based abstractions of timed automata"
      * (2006). The result contains the zone and lies in its closure under region equivalence for
      * {@code max}. {@code max[x]} is the largest constant clock {@code x} is compared with; a
      * negative entry means none, and the clock is then freed. {@code max[0]} is not read.
      *
      * @throws IllegalArgumentException if {@code max.length != dimension()} or an entry exceeds
      *     {@link Bound#MAX_VALUE}
      */
    public void extrapolateMaxBounds(int[] max) {
        checkConstants(max);
        if (isEmpty()) {
            return;
        }
        Weakened changed = new Weakened();
        for (int j = 1; j < dim; j++) {
            int b = clampLower(m[j], max[j]);
            changed.set(0, j, b);
        }
        for (int i = 1; i < dim; i++) {
            int rowI = i * dim;
            int above = max[i] < 0 ? Integer.MIN_VALUE : Bound.le(max[i]);
            for (int j = 0; j < dim; j++) {
                int b = m[rowI + j];
                if (j == i || b == INFINITY) {
                    continue;
                }
                int weaker = b > above ? INFINITY : j == 0 ? b : clampDifference(b, max[j]);
                changed.set(i, j, weaker);
            }
        }
        changed.close();
    }


    /**
      * Extrapolates the zone with lower and upper bounds: the operator Extra+_LU of Behrmann, Bouyer,
      * Larsen and Pelánek, "Lower and upper bounds in zone-based abstractions of timed automata"
      * (2006). The result contains the zone and lies in its abstraction by LU-simulation. {@code
      * lower[x]} ({@code upper[x]}) is the largest constant in a lower-bound guard {@code x > c},
      * {@code x >= c} (upper-bound guard or invariant {@code x < c}, {@code x <= c}); a negative
      * entry means there is none. Index 0 is not read.
      *
      * @throws IllegalArgumentException if an array's length is not {@code dimension()} or an entry
      *     exceeds {@link Bound#MAX_VALUE}
      */
    public void extrapolateLU(int[] lower, int[] upper) {
        checkConstants(lower);
        checkConstants(upper);
        if (isEmpty()) {
            return;
        }
        Weakened changed = new Weakened();
        int[] d = m;
        int n = dim;
        // The columns j whose lower bound is above U_j (or that have no U_j): bit j, read off row 0 before it is
        // rewritten; recomputed per entry only beyond 64 clocks.
        boolean wide = n > Long.SIZE;
        long freeColumns = 0;
        for (int j = 1; j < n && !wide; j++) {
            if (upper[j] < 0 || d[j] < Bound.le(-upper[j])) {
                freeColumns |= 1L << j;
            }
        }
        // Rows 1.. first: their conditions read row 0 before it is rewritten.
        for (int i = 1; i < n; i++) {
            int rowI = i * n;
            boolean aboveLower = lower[i] < 0 || d[i] < Bound.le(-lower[i]);
            int above = aboveLower ? Integer.MIN_VALUE : Bound.le(lower[i]);
            for (int j = 0; j < n; j++) {
                int b = d[rowI + j];
                if (j == i || b == INFINITY) {
                    continue;
                }
                boolean freeColumn = wide ? j != 0 && (upper[j] < 0 || d[j] < Bound.le(-upper[j]))
                        : (freeColumns >>> j & 1) != 0;
                if (b > above || freeColumn) {
                    changed.set(i, j, INFINITY);
                }
            }
        }
        for (int j = 1; j < n; j++) {
            int b = clampLower(d[j], upper[j]);
            changed.set(0, j, b);
        }
        changed.close();
    }

    /**
      * The entries an extrapolation raised (weakened) in this closed, non-empty matrix, and the closure after
      * them. Every other entry is still the shortest path between its clocks (paths only got longer), so
      * Floyd-Warshall need only update the raised ones: O(n) per raised entry instead of O(n^3) in all.
      */
    private final class Weakened {
        /** Per row, the columns of its raised entries as bits (dimensions up to 64); allocated at the first. */
        private long[] columns;
        private int count;

        /** Sets entry ({@code i}, {@code j}) to {@code b}, no tighter than it was. */
        void set(int i, int j, int b) {
            int ij = i * dim + j;
            if (b == m[ij]) {
                return;
            }
            m[ij] = b;
            if (dim > Long.SIZE) {
                count = m.length;
                return;
            }
            if (columns == null) {
                columns = new long[dim];
            }
            columns[i] |= 1L << j;
            count++;
        }

        /** Restores the canonical form. */
        void close() {
            if (count == 0) {
                return;
            }
            if (2 * count > m.length) {
                Dbm.this.close();
                return;
            }
            int[] d = m;
            int n = dim;
            long[] cols = columns;
            for (int k = 0; k < n; k++) {
                int rowK = k * n;
                if (unbounded(rowK, k)) {
                    continue;
                }
                for (int i = 0; i < n; i++) {
                    long bits = cols[i];
                    if (bits == 0) {
                        continue;
                    }
                    int rowI = i * n;
                    int ik = d[rowI + k];
                    if (ik == INFINITY) {
                        continue;
                    }
                    while (bits != 0) {
                        int j = Long.numberOfTrailingZeros(bits);
                        bits &= bits - 1;
                        int kj = d[rowK + j];
                        // Bound.add inlined: for finite bounds only the lower clamp can apply to a tighter sum;
                        // written without branches, as whether a sum is tighter is hard to predict
                        long sum = kj == INFINITY ? Long.MAX_VALUE : (long) ik + kj - ((ik | kj) & 1);
                        d[rowI + j] = (int) Math.min(d[rowI + j], Math.max(sum, MIN_RAW));
                    }
                }
            }
        }
    }

    /**
      * Returns true for a zone of the same dimension holding the same valuations.
      */
    @Override
    public boolean equals(Object o) {
        return o instanceof Dbm && ((Dbm) o).dim == dim && Arrays.equals(((Dbm) o).m, m);
    }

    /** Returns a hash of the canonical matrix; it changes when the zone is mutated. */
    @Override
    public int hashCode() {
        return Arrays.hashCode(m);
    }

    /**
      * Returns the zone as a conjunction of constraints on clocks named {@code x1, x2, ...}, for
      * example {@code "x1<=5, x2>2, x1-x2<3"}; {@code "true"} if unconstrained, {@code "false"} if
      * empty. See {@link #toString(String[])}.
      */
    @Override
    public String toString() {
        return describe(null);
    }

    /**
      * Returns the zone as a conjunction of constraints on clocks named by {@code clockNames} (index
      * 0 is not read): clock bounds, then differences not implied by the clock bounds; {@code "true"}
      * if unconstrained, {@code "false"} if empty.
      *
      * @throws IllegalArgumentException if {@code clockNames.length != dimension()}
      */
    public String toString(String[] clockNames) {
        if (clockNames.length != dim) {
            throw new IllegalArgumentException("need " + dim + " clock names");
        }
        return describe(clockNames);
    }

    private String describe(String[] names) {
        if (isEmpty()) {
            return "false";
        }
        StringBuilder sb = new StringBuilder();
        for (int i = 1; i < dim; i++) {
            String x = names == null ? "x" + i : names[i];
            appendRange(sb, x, m[i], m[i * dim], LE_ZERO);
        }
        for (int i = 1; i < dim; i++) {
            for (int j = i + 1; j < dim; j++) {
                String x = names == null ? "x" + i + "-x" + j : names[i] + "-" + names[j];
                int upperImplied = Bound.add(m[i * dim], m[j]);
                int lowerImplied = Bound.add(m[j * dim], m[i]);
                int upper = m[i * dim + j] < upperImplied ? m[i * dim + j] : INFINITY;
                int lowerNeg = m[j * dim + i] < lowerImplied ? m[j * dim + i] : INFINITY;
                appendRange(sb, x, lowerNeg, upper, INFINITY);
            }
        }
        return sb.length() == 0 ? "true" : sb.toString();
    }

    /** Appends "term ⋈ c" for the range given by a bound on -term and a bound on term. */
    private static void appendRange(
            StringBuilder sb, String term, int lowerNeg, int upper, int trivial) {
        boolean hasUpper = upper != INFINITY;
        if (hasUpper && lowerNeg != INFINITY && !Bound.isStrict(lowerNeg) && !Bound.isStrict(upper)
                && (lowerNeg >> 1) == -(upper >> 1)) {
            separate(sb).append(term).append("==").append(upper >> 1);
            return;
        }
        if (lowerNeg != trivial && lowerNeg != INFINITY) {
            separate(sb).append(term).append(Bound.isStrict(lowerNeg) ? ">" : ">=")
                    .append(-(lowerNeg >> 1));
        }
        if (hasUpper) {
            separate(sb).append(term).append(Bound.toString(upper));
        }
    }

    private static StringBuilder separate(StringBuilder sb) {
        return sb.length() == 0 ? sb : sb.append(", ");
    }

    /** Weakens a lower-bound entry (0, x) below {@code x > max} to {@code x > max}. */
    private static int clampLower(int b, int max) {
        if (max < 0) {
            return LE_ZERO;
        }
        return b < Bound.le(-max) ? Bound.lt(-max) : b;
    }

    /** Weakens a difference entry (i, x), i > 0, below {@code -max} to {@code < -max}. */
    private static int clampDifference(int b, int max) {
        if (max < 0) {
            return INFINITY;
        }
        return b < Bound.le(-max) ? Bound.lt(-max) : b;
    }

    /** Floyd-Warshall closure; returns false (and marks the zone empty) on a negative cycle. */
    private boolean close() {
        int[] d = m;
        int n = dim;
        for (int k = 0; k < n; k++) {
            int rowK = k * n;
            if (unbounded(rowK, k)) {
                continue;
            }
            for (int i = 0; i < n; i++) {
                int rowI = i * n;
                int ik = d[rowI + k];
                if (i == k || ik == INFINITY) {
                    continue;
                }
                for (int j = 0; j < n; j++) {
                    int kj = d[rowK + j];
                    // Bound.add inlined (for finite bounds only the lower clamp can apply to a tighter sum),
                    // without branches: whether a sum is tighter is hard to predict
                    long sum = kj == INFINITY ? Long.MAX_VALUE : (long) ik + kj - ((ik | kj) & 1);
                    d[rowI + j] = (int) Math.min(d[rowI + j], Math.max(sum, MIN_RAW));
                }
                if (d[rowI + i] < LE_ZERO) {
                    makeEmpty();
                    return false;
                }
            }
        }
        return true;
    }

    /**
      * Whether every entry of row {@code k} (at offset {@code rowK}) but the diagonal is infinite: no path through
      * clock {@code k} is then shorter than the direct one (an extrapolation frees the rows of the clocks above their
      * constants), so a closure may skip it as the intermediate clock.
      */
    private boolean unbounded(int rowK, int k) {
        for (int j = 0; j < dim; j++) {
            if (j != k && m[rowK + j] != INFINITY) {
                return false;
            }
        }
        return true;
    }

    private void makeEmpty() {
        Arrays.fill(m, LT_ZERO);
    }

    private void checkClock(int x) {
        if (x < 1 || x >= dim) {
            throw new IndexOutOfBoundsException("clock index " + x + " not in 1.." + (dim - 1));
        }
    }

    private void checkConstants(int[] perClock) {
        if (perClock.length != dim) {
            throw new IllegalArgumentException("need " + dim + " entries, got " + perClock.length);
        }
        for (int x = 1; x < dim; x++) {
            if (perClock[x] > Bound.MAX_VALUE) {
                throw new IllegalArgumentException("constant out of range: " + perClock[x]);
            }
        }
    }

    private void checkSameDimension(Dbm other) {
        if (other.dim != dim) {
            throw new IllegalArgumentException("dimensions differ: " + dim + " and " + other.dim);
        }
    }
}
