package io.dtron.engine.internal.zone;

import static io.dtron.engine.internal.zone.Zones.assertCanonical;
import static io.dtron.engine.internal.zone.Zones.existsGridPoint;
import static io.dtron.engine.internal.zone.Zones.gridDen;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.zone.Zones.Constraint;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Collections;
import java.util.EnumMap;
import java.util.List;
import java.util.Map;
import java.util.Random;
import java.util.function.Predicate;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;

/**
  * Compares every zone operation with its semantic definition, checked exactly on rational grid
  * points, over random zones of 1 to 4 clocks built by random operation sequences with constants
  * up to {@link #MAX_CONST}.
  *
  * <p>Membership is sampled on the grid of multiples of {@code 1/(2n+2)} (n clocks) in {@code [0,
  * MAX_CONST + 2]}: every region, so every non-empty zone with integer constants, has points on
  * the coarser grid {@code 1/(n+1)}, and the finer grid also places points strictly between them,
  * at half units and off every integer diagonal, so strict and non-strict bounds and diagonal
  * constraints all separate points. Questions of existence ("is this bounded set empty?") are
  * decided by exhaustive search of the {@code 1/(n+1)} grid; see {@link Zones#existsGridPoint}.
  */
class DbmPropertyTest {

    private static final int MAX_CONST = 4;
    private static final int MAX_VALUE = MAX_CONST + 2;
    private static final int ZONES = 300;
    private static final int POINTS = 250;

    /** Runs {@code body} for {@code cases} cases, with dimensions 2..5 in turn, from a fixed seed. */
    private static void forCases(long seed, int cases, CaseBody body) {
        Random r = new Random(seed);
        for (int c = 0; c < cases; c++) {
            body.run(r, 2 + c % 4);
        }
    }

    @FunctionalInterface
    private interface CaseBody {
        void run(Random r, int dim);
    }

    /** The sampling denominator {@code 2n+2} for n clocks. */
    private static long den(int dim) {
        return 2L * dim;
    }

    /** Counts sampled points inside and outside a result, to show a property is not vacuous. */
    private static final class Tally {
        long in;
        long out;

        void check(boolean expected, boolean actual, String what, Dbm zone, long[] v) {
            assertEquals(expected, actual, () -> what + " at " + Arrays.toString(v) + " in " + zone);
            if (actual) {
                in++;
            } else {
                out++;
            }
        }

        void assertBothSeen(long atLeast) {
            assertTrue(in >= atLeast && out >= atLeast, "too few points inside/outside: " + in + "/" + out);
        }
    }

    @Test
    void constraintsAgreeWithTheirConjunction() {
        Tally tally = new Tally();
        forCases(1, ZONES, (r, dim) -> {
            List<Constraint> cs = new ArrayList<>();
            Dbm z = Dbm.unconstrained(dim);
            int k = 1 + r.nextInt(2 * dim);
            for (int s = 0; s < k; s++) {
                Constraint c = Zones.randomConstraint(r, dim, MAX_CONST);
                cs.add(c);
                assertEquals(z.copy().constrain(c.i(), c.j(), c.raw()), z.satisfies(c.i(), c.j(), c.raw()),
                        "satisfies agrees with constrain for " + c + " on " + z);
                boolean nonEmpty = z.constrain(c.i(), c.j(), c.raw());
                assertEquals(!z.isEmpty(), nonEmpty);
                assertCanonical(z);
            }
            for (long[] v : Zones.points(r, z, den(dim), MAX_VALUE, POINTS)) {
                boolean all = cs.stream().allMatch(c -> c.holds(v, den(dim)));
                tally.check(all, z.contains(v, den(dim)), "conjunction " + cs, z, v);
            }
        });
        tally.assertBothSeen(1000);
    }

    @Test
    void constrainAllEqualsConstrainingOneAtATime() {
        int[] seen = new int[2];
        forCases(17, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST);
            if (r.nextBoolean()) {
                z.up();
            }
            int count = 1 + r.nextInt(2 * dim);
            int[] triples = new int[3 * count];
            for (int k = 0; k < count; k++) {
                // mostly upper bounds of one clock, as invariants give them
                Constraint c = Zones.randomConstraint(r, dim, MAX_CONST);
                boolean upper = r.nextInt(3) > 0;
                triples[3 * k] = upper ? 1 + r.nextInt(dim - 1) : c.i();
                triples[3 * k + 1] = upper ? 0 : c.j();
                triples[3 * k + 2] = upper ? Bound.of(r.nextInt(MAX_CONST + 1), r.nextBoolean()) : c.raw();
            }
            Dbm one = z.copy();
            boolean nonEmpty = true;
            for (int k = 0; k < count && nonEmpty; k++) {
                nonEmpty = one.constrain(triples[3 * k], triples[3 * k + 1], triples[3 * k + 2]);
            }
            Dbm all = z.copy();
            assertEquals(nonEmpty, all.constrainAll(triples), () -> "emptiness of " + Arrays.toString(triples));
            assertEquals(one, all, () -> Arrays.toString(triples) + " on " + z);
            assertCanonical(all);
            seen[nonEmpty ? 1 : 0]++;
        });
        assertTrue(seen[0] > 10 && seen[1] > 10, "empty/non-empty " + seen[0] + "/" + seen[1]);
    }

    @Test
    void emptinessAgreesWithExhaustiveSearch() {
        int[] seen = new int[2];
        forCases(2, ZONES, (r, dim) -> {
            int bound = dim == 5 ? 3 : MAX_CONST;
            List<Constraint> cs = new ArrayList<>();
            Dbm z = Zones.bounded(Dbm.unconstrained(dim), bound);
            Dbm box = z.copy();
            for (int s = 1 + r.nextInt(2 * dim); s > 0; s--) {
                Constraint c = Zones.randomConstraint(r, dim, MAX_CONST);
                cs.add(c);
                z.constrain(c.i(), c.j(), c.raw());
            }
            long den = gridDen(z);
            boolean exists = existsGridPoint(box, v -> cs.stream().allMatch(c -> c.holds(v, den)));
            assertEquals(!exists, z.isEmpty(), () -> "emptiness of " + cs);
            seen[exists ? 1 : 0]++;
            // A zone built by other operations, once bounded, is non-empty iff it has a grid point.
            Dbm built = Zones.bounded(Zones.randomZone(r, dim, MAX_CONST), bound);
            if (!built.isEmpty()) {
                assertTrue(existsGridPoint(built, v -> built.contains(v, den)), () -> "no point in " + built);
            }
        });
        assertTrue(seen[0] > 20 && seen[1] > 20, "empty/non-empty cases: " + Arrays.toString(seen));
    }

    @Test
    void constrainOfBuiltZones() {
        Tally tally = new Tally();
        forCases(3, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST);
            Constraint c = Zones.randomConstraint(r, dim, MAX_CONST);
            Dbm result = z.copy();
            boolean nonEmpty = result.constrain(c.i(), c.j(), c.raw());
            assertEquals(!result.isEmpty(), nonEmpty);
            assertCanonical(result);
            for (long[] v : Zones.points(r, z, den(dim), MAX_VALUE, POINTS)) {
                tally.check(z.contains(v, den(dim)) && c.holds(v, den(dim)), result.contains(v, den(dim)),
                        z + " and " + c, result, v);
            }
        });
        tally.assertBothSeen(1000);
    }

    @Test
    void upIsTheFuture() {
        Tally tally = new Tally();
        forCases(4, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST);
            Dbm result = z.copy();
            result.up();
            assertCanonical(result);
            long den = den(dim);
            long[] w = new long[dim];
            for (long[] v : Zones.points(r, result, den, MAX_VALUE, POINTS)) {
                // The delays d >= 0 with v - d in z form an interval whose ends (0, v_x, v_x - c, v_y + c)
                // are multiples of 1/den, bounded by min v_x; if non-empty it holds a closed end or the
                // midpoint of its ends, both multiples of 1/(2 den): searching those is exact.
                long min = Long.MAX_VALUE;
                for (int x = 1; x < dim; x++) {
                    min = Math.min(min, v[x]);
                }
                boolean expected = false;
                for (long k = 0; k <= 2 * min && !expected; k++) {
                    for (int x = 1; x < dim; x++) {
                        w[x] = 2 * v[x] - k;
                    }
                    expected = z.contains(w, 2 * den);
                }
                tally.check(expected, result.contains(v, den), "up of " + z, result, v);
            }
        });
        tally.assertBothSeen(1000);
    }

    @Test
    void downIsThePast() {
        Tally tally = new Tally();
        forCases(5, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST);
            Dbm result = z.copy();
            result.down();
            assertCanonical(result);
            long den = den(dim);
            long[] w = new long[dim];
            // The delays d >= 0 with v + d in z form an interval with ends 0, c - v_x, -c - v_x, all
            // multiples of 1/den and at most the largest constant; searching multiples of 1/(2 den) up
            // to that constant plus one finds a closed end, a midpoint, or a point past a finite lower end.
            long limit = 2 * den * (Zones.maxConstant(z) + 1);
            for (long[] v : Zones.points(r, result, den, MAX_VALUE, POINTS)) {
                boolean expected = false;
                for (long k = 0; k <= limit && !expected; k++) {
                    for (int x = 1; x < dim; x++) {
                        w[x] = 2 * v[x] + k;
                    }
                    expected = z.contains(w, 2 * den);
                }
                tally.check(expected, result.contains(v, den), "down of " + z, result, v);
            }
        });
        tally.assertBothSeen(1000);
    }

    /**
      * Returns whether some {@code t >= 0} puts {@code v[x := t]} in {@code z}. The feasible values
      * of t form an interval with ends 0, {@code v_y ± c} and c, multiples of 1/den bounded by the
      * largest coordinate plus the largest constant; searching multiples of 1/(2 den) up to one past
      * that finds a closed end, a midpoint or a point past a finite lower end: the search is exact.
      */
    private static boolean someValueOf(Dbm z, int x, long[] v, long den, long[] w) {
        long max = 0;
        for (int y = 1; y < v.length; y++) {
            max = Math.max(max, v[y]);
            w[y] = 2 * v[y];
        }
        long limit = 2 * max + 2 * den * (Zones.maxConstant(z) + 1);
        for (long t = 0; t <= limit; t++) {
            w[x] = t;
            if (z.contains(w, 2 * den)) {
                return true;
            }
        }
        return false;
    }

    @Test
    void resetAssignsAConstant() {
        Tally tally = new Tally();
        forCases(6, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST);
            int x = 1 + r.nextInt(dim - 1);
            int value = r.nextInt(MAX_CONST + 1);
            Dbm result = z.copy();
            result.reset(x, value);
            assertCanonical(result);
            long den = den(dim);
            long[] w = new long[dim];
            for (long[] v : Zones.points(r, result, den, MAX_VALUE, POINTS)) {
                boolean expected = v[x] == value * den && someValueOf(z, x, v, den, w);
                tally.check(expected, result.contains(v, den), "x" + x + ":=" + value + " on " + z, result, v);
            }
        });
        tally.assertBothSeen(1000);
    }

    @Test
    void freeForgetsAClock() {
        Tally tally = new Tally();
        forCases(7, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST);
            int x = 1 + r.nextInt(dim - 1);
            Dbm result = z.copy();
            result.free(x);
            assertCanonical(result);
            long den = den(dim);
            long[] w = new long[dim];
            for (long[] v : Zones.points(r, result, den, MAX_VALUE, POINTS)) {
                tally.check(someValueOf(z, x, v, den, w), result.contains(v, den), "free x" + x + " of " + z, result, v);
            }
        });
        tally.assertBothSeen(1000);
    }

    @Test
    void copyClockAssignsAClock() {
        Tally tally = new Tally();
        forCases(8, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST);
            int x = 1 + r.nextInt(dim - 1);
            int y = r.nextInt(dim);
            Dbm result = z.copy();
            result.copyClock(x, y);
            assertCanonical(result);
            long den = den(dim);
            long[] w = new long[dim];
            for (long[] v : Zones.points(r, result, den, MAX_VALUE, POINTS)) {
                boolean expected = x == y ? z.contains(v, den) : v[x] == v[y] && someValueOf(z, x, v, den, w);
                tally.check(expected, result.contains(v, den), "x" + x + ":=x" + y + " on " + z, result, v);
            }
        });
        tally.assertBothSeen(1000);
    }

    @Test
    void intersectionIsPointwise() {
        Tally tally = new Tally();
        int[] empties = new int[1];
        forCases(9, ZONES, (r, dim) -> {
            Dbm a = Zones.randomZone(r, dim, MAX_CONST);
            Dbm b = Zones.randomZone(r, dim, MAX_CONST);
            Dbm ab = a.copy();
            Dbm ba = b.copy();
            boolean nonEmpty = ab.intersect(b);
            assertEquals(!ab.isEmpty(), nonEmpty);
            ba.intersect(a);
            assertCanonical(ab);
            assertEquals(ab, ba, "intersection commutes");
            long den = den(dim);
            for (long[] v : Zones.points(r, r.nextBoolean() ? a : b, den, MAX_VALUE, POINTS)) {
                tally.check(a.contains(v, den) && b.contains(v, den), ab.contains(v, den), a + " and " + b, ab, v);
            }
            // Bounded, the emptiness of the intersection is decided exactly.
            Dbm boundedA = Zones.bounded(a.copy(), MAX_CONST);
            Dbm boundedB = Zones.bounded(b.copy(), MAX_CONST);
            Dbm boundedAb = Zones.bounded(ab.copy(), MAX_CONST);
            if (!boundedA.isEmpty()) {
                long gden = gridDen(a);
                boolean exists = existsGridPoint(boundedA, v -> boundedA.contains(v, gden) && boundedB.contains(v, gden));
                assertEquals(!exists, boundedAb.isEmpty(), () -> "emptiness of " + a + " and " + b);
                empties[0] += exists ? 0 : 1;
            }
        });
        tally.assertBothSeen(1000);
        assertTrue(empties[0] > 20, "empty intersections: " + empties[0]);
    }

    @Test
    void satisfiesMeansSomePointMeetsTheConstraint() {
        int[] outcomes = new int[2];
        forCases(10, ZONES, (r, dim) -> {
            Dbm z = Zones.bounded(Zones.randomZone(r, dim, MAX_CONST), MAX_CONST);
            if (z.isEmpty()) {
                return;
            }
            Constraint c = Zones.randomConstraint(r, dim, MAX_CONST);
            long den = gridDen(z);
            boolean exists = existsGridPoint(z, v -> z.contains(v, den) && c.holds(v, den));
            assertEquals(exists, z.satisfies(c.i(), c.j(), c.raw()), () -> z + " meets " + c);
            outcomes[exists ? 1 : 0]++;
        });
        assertTrue(outcomes[0] > 20 && outcomes[1] > 20, Arrays.toString(outcomes));
    }

    @Test
    void boundsAreTightAndLowerMirrorsUpper() {
        forCases(11, ZONES, (r, dim) -> {
            Dbm z = Zones.bounded(Zones.randomZone(r, dim, MAX_CONST), MAX_CONST);
            if (z.isEmpty()) {
                return;
            }
            long den = gridDen(z);
            for (int i = 0; i < dim; i++) {
                for (int j = 0; j < dim; j++) {
                    int b = z.upperBound(i, j);
                    assertTrue(b != Bound.INFINITY, "bounded zone has finite bounds");
                    int fi = i;
                    int fj = j;
                    long c = Bound.value(b);
                    // "<= c" is attained; "< c" is approached: some point lies above c - 1 (no integer
                    // bound in between is tighter).
                    boolean tight = existsGridPoint(z, v -> z.contains(v, den)
                            && (Bound.isStrict(b) ? v[fi] - v[fj] > (c - 1) * den : v[fi] - v[fj] == c * den));
                    assertTrue(tight, () -> "bound " + Bound.toString(b) + " on x" + fi + "-x" + fj + " not tight in " + z);
                    int lower = z.lowerBound(j, i);
                    assertEquals(-c, Bound.value(lower));
                    assertEquals(Bound.isStrict(b), Bound.isStrict(lower));
                }
                assertEquals(z.upperBound(i, 0), z.upperBound(i));
                assertEquals(z.lowerBound(i, 0), z.lowerBound(i));
            }
        });
    }

    @Test
    void relationAgreesWithPointSets() {
        Map<Relation, Integer> seen = new EnumMap<>(Relation.class);
        forCases(12, ZONES, (r, dim) -> {
            int bound = dim == 5 ? 3 : MAX_CONST;
            Dbm a = Zones.randomZone(r, dim, MAX_CONST);
            Dbm b = a.copy();
            switch (r.nextInt(5)) {
                case 0 -> b = Zones.randomZone(r, dim, MAX_CONST);
                case 1 -> {
                    Constraint c = Zones.randomConstraint(r, dim, MAX_CONST);
                    b.constrain(c.i(), c.j(), c.raw());
                }
                case 2 -> b.up();
                case 3 -> b.free(1 + r.nextInt(dim - 1));
                default -> b.intersect(Zones.randomZone(r, dim, MAX_CONST));
            }
            Dbm fa = Zones.bounded(r.nextBoolean() ? a : b, bound);
            Dbm fb = Zones.bounded(fa == a ? b : a, bound);
            long den = gridDen(a);
            boolean aInB = fa.isEmpty() || !existsGridPoint(fa, v -> fa.contains(v, den) && !fb.contains(v, den));
            boolean bInA = fb.isEmpty() || !existsGridPoint(fb, v -> fb.contains(v, den) && !fa.contains(v, den));
            Relation expected = aInB ? (bInA ? Relation.EQUAL : Relation.SUBSET)
                    : bInA ? Relation.SUPERSET : Relation.DIFFERENT;
            assertEquals(expected, fa.relation(fb), () -> fa + " vs " + fb);
            assertEquals(aInB, fa.isSubsetOf(fb));
            assertEquals(bInA, fb.isSubsetOf(fa));
            assertEquals(expected == Relation.EQUAL, fa.equals(fb));
            if (expected == Relation.EQUAL) {
                assertEquals(fa.hashCode(), fb.hashCode());
            }
            seen.merge(expected, 1, Integer::sum);
        });
        for (Relation rel : Relation.values()) {
            assertTrue(seen.getOrDefault(rel, 0) > 10, "relations seen: " + seen);
        }
    }

    @Test
    void canonicalFormIsUniqueAndToStringDescribesTheZone() {
        forCases(13, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST);
            // Rebuild from the matrix entries in random order: same canonical matrix.
            Dbm rebuilt = Dbm.unconstrained(dim);
            List<int[]> entries = new ArrayList<>();
            for (int i = 0; i < dim; i++) {
                for (int j = 0; j < dim; j++) {
                    entries.add(new int[] {i, j});
                }
            }
            Collections.shuffle(entries, r);
            for (int[] e : entries) {
                rebuilt.constrain(e[0], e[1], z.upperBound(e[0], e[1]));
            }
            assertEquals(z, rebuilt);
            assertEquals(z.hashCode(), rebuilt.hashCode());
            assertEquals(z, parse(z.toString(), dim), () -> "toString " + z);
        });
    }

    private static final Pattern ATOM = Pattern.compile("x(\\d+)(?:-x(\\d+))?(<=|<|>=|>|==)(-?\\d+)");

    /** Reads back the output of {@link Dbm#toString()}. */
    private static Dbm parse(String text, int dim) {
        Dbm z = Dbm.unconstrained(dim);
        if (text.equals("true")) {
            return z;
        }
        for (String atom : text.split(", ")) {
            Matcher m = ATOM.matcher(atom);
            assertTrue(m.matches(), atom);
            int i = Integer.parseInt(m.group(1));
            int j = m.group(2) == null ? 0 : Integer.parseInt(m.group(2));
            int c = Integer.parseInt(m.group(4));
            switch (m.group(3)) {
                case "<=" -> z.constrain(i, j, Bound.le(c));
                case "<" -> z.constrain(i, j, Bound.lt(c));
                case ">=" -> z.constrain(j, i, Bound.le(-c));
                case ">" -> z.constrain(j, i, Bound.lt(-c));
                default -> {
                    z.constrain(i, j, Bound.le(c));
                    z.constrain(j, i, Bound.le(-c));
                }
            }
        }
        return z;
    }

    /** Random per-clock constants in [-1, MAX_CONST] (-1: the clock is compared with nothing). */
    private static int[] randomMax(Random r, int dim) {
        int[] max = new int[dim];
        for (int x = 1; x < dim; x++) {
            max[x] = r.nextInt(8) == 0 ? -1 : r.nextInt(MAX_CONST + 1);
        }
        return max;
    }

    private static int[] huge(int dim) {
        int[] max = new int[dim];
        Arrays.fill(max, 1000);
        return max;
    }

    @Test
    void extrapolateMaxBoundsStaysWithinTheRegionClosure() {
        Tally tally = new Tally();
        long[] grew = new long[1];
        forCases(14, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST + 2);
            int[] max = randomMax(r, dim);
            Dbm e = z.copy();
            e.extrapolateMaxBounds(max);
            assertCanonical(e);
            assertTrue(z.isSubsetOf(e), () -> "extrapolation of " + z + " lost points: " + e);
            Dbm again = e.copy();
            again.extrapolateMaxBounds(max);
            assertEquals(e, again, "idempotent");
            Dbm same = z.copy();
            same.extrapolateMaxBounds(huge(dim));
            assertEquals(z, same, "large constants change nothing");
            Dbm lu = z.copy();
            lu.extrapolateLU(max, max);
            assertTrue(e.isSubsetOf(lu), "Extra_M is finer than Extra+_LU with L = U = M");
            long den = den(dim);
            Dbm scaled = Zones.scaled(z, (int) den);
            for (long[] v : Zones.points(r, e, den, MAX_VALUE + 2, POINTS)) {
                boolean inZ = z.contains(v, den);
                boolean inE = e.contains(v, den);
                assertTrue(!inZ || inE, "superset");
                tally.check(inE, inE && regionMeets(scaled, v, den, max), "region closure", e, v);
                grew[0] += inE && !inZ ? 1 : 0;
            }
        });
        tally.assertBothSeen(1000);
        assertTrue(grew[0] > 1000, "points added by extrapolation: " + grew[0]);
    }

    /**
      * Returns whether the region of {@code v} (numerators over den) for maximal constants {@code
      * max} meets the zone {@code scaled}, given with constants multiplied by den.
      */
    private static boolean regionMeets(Dbm scaled, long[] v, long den, int[] max) {
        int dim = v.length;
        Dbm region = scaled.copy();
        for (int x = 1; x < dim; x++) {
            if (max[x] < 0) {
                continue;
            }
            if (v[x] > max[x] * den) {
                region.constrain(0, x, Bound.lt((int) (-max[x] * den)));
            } else if (v[x] % den == 0) {
                region.constrain(x, 0, Bound.le((int) v[x]));
                region.constrain(0, x, Bound.le((int) -v[x]));
            } else {
                long floor = v[x] / den * den;
                region.constrain(0, x, Bound.lt((int) -floor));
                region.constrain(x, 0, Bound.lt((int) (floor + den)));
                for (int y = 1; y < x; y++) {
                    if (max[y] < 0 || v[y] > max[y] * den || v[y] % den == 0) {
                        continue;
                    }
                    long diff = floor - v[y] / den * den;
                    long fx = v[x] % den;
                    long fy = v[y] % den;
                    if (fx <= fy) {
                        region.constrain(x, y, fx == fy ? Bound.le((int) diff) : Bound.lt((int) diff));
                    }
                    if (fx >= fy) {
                        region.constrain(y, x, fx == fy ? Bound.le((int) -diff) : Bound.lt((int) -diff));
                    }
                }
            }
        }
        return !region.isEmpty();
    }

    @Test
    void extrapolateLuStaysWithinTheLuAbstraction() {
        Tally tally = new Tally();
        long[] grew = new long[1];
        forCases(15, ZONES, (r, dim) -> {
            Dbm z = Zones.randomZone(r, dim, MAX_CONST + 2);
            int[] lower = randomMax(r, dim);
            int[] upper = randomMax(r, dim);
            Dbm e = z.copy();
            e.extrapolateLU(lower, upper);
            assertCanonical(e);
            assertTrue(z.isSubsetOf(e), () -> "extrapolation of " + z + " lost points: " + e);
            Dbm again = e.copy();
            again.extrapolateLU(lower, upper);
            assertEquals(e, again, "idempotent");
            Dbm same = z.copy();
            same.extrapolateLU(huge(dim), huge(dim));
            assertEquals(z, same, "large constants change nothing");
            int[] max = new int[dim];
            for (int x = 1; x < dim; x++) {
                max[x] = Math.max(lower[x], upper[x]);
            }
            Dbm m = z.copy();
            m.extrapolateMaxBounds(max);
            assertTrue(m.isSubsetOf(e), "Extra_M with M = max(L, U) is finer than Extra+_LU");
            long den = den(dim);
            Dbm scaled = Zones.scaled(z, (int) den);
            for (long[] v : Zones.points(r, e, den, MAX_VALUE + 2, POINTS)) {
                boolean inZ = z.contains(v, den);
                boolean inE = e.contains(v, den);
                assertTrue(!inZ || inE, "superset");
                tally.check(inE, inE && simulatedBy(scaled, v, den, lower, upper), "LU abstraction", e, v);
                grew[0] += inE && !inZ ? 1 : 0;
            }
        });
        tally.assertBothSeen(1000);
        assertTrue(grew[0] > 1000, "points added by extrapolation: " + grew[0]);
    }

    /**
      * Returns whether some point v' of the zone {@code scaled} (constants multiplied by den)
      * LU-simulates {@code v}: for every clock, {@code v'_x = v_x}, or {@code L_x < v'_x < v_x}, or
      * {@code U_x < v_x < v'_x}. Per clock these choices form an interval, so the candidates v' form
      * a box, intersected exactly with the zone.
      */
    private static boolean simulatedBy(Dbm scaled, long[] v, long den, int[] lower, int[] upper) {
        Dbm box = scaled.copy();
        for (int x = 1; x < v.length; x++) {
            boolean aboveL = lower[x] < 0 || v[x] > lower[x] * den;
            boolean aboveU = upper[x] < 0 || v[x] > upper[x] * den;
            if (aboveL && lower[x] >= 0) {
                box.constrain(0, x, Bound.lt((int) (-lower[x] * den)));
            }
            if (!aboveL) {
                box.constrain(0, x, Bound.le((int) -v[x]));
            }
            if (!aboveU) {
                box.constrain(x, 0, Bound.le((int) v[x]));
            }
        }
        return !box.isEmpty();
    }

    /**
      * The extrapolations give exactly the closure of the matrix their definitions weaken entry by entry (closed
      * here by adding every finite entry to the unconstrained zone), on zones of up to 9 clocks where many clocks lie
      * above their constants: the closure after an extrapolation skips the clocks whose rows it freed.
      */
    @Test
    void extrapolationsCloseExactlyTheWeakenedMatrix() {
        Random r = new Random(17);
        int freedRows = 0;
        for (int c = 0; c < 3000; c++) {
            int dim = 2 + c % 9;
            Dbm z = Zones.randomZone(r, dim, MAX_CONST + 2);
            for (int s = r.nextInt(3); s > 0; s--) {
                z.up();
                z.reset(1 + r.nextInt(dim - 1), 0);
            }
            int[] lower = randomMax(r, dim);
            int[] upper = randomMax(r, dim);
            int[] max = randomMax(r, dim);
            int[][] lu = new int[dim][dim];
            int[][] m = new int[dim][dim];
            for (int i = 0; i < dim; i++) {
                for (int j = 0; j < dim; j++) {
                    int b = z.upperBound(i, j);
                    boolean free = i > 0 && (lower[i] < 0 || z.upperBound(0, i) < Bound.le(-lower[i])
                            || b > Bound.le(lower[i])
                            || j > 0 && (upper[j] < 0 || z.upperBound(0, j) < Bound.le(-upper[j])));
                    lu[i][j] = i == j ? b : i == 0 ? clamp(b, upper[j], Bound.LE_ZERO) : free ? Bound.INFINITY : b;
                    int maxRow = max[i] < 0 ? Integer.MIN_VALUE : Bound.le(max[i]);
                    m[i][j] = i == j ? b : i == 0 ? clamp(b, max[j], Bound.LE_ZERO)
                            : b > maxRow ? Bound.INFINITY : j == 0 ? b : clamp(b, max[j], Bound.INFINITY);
                }
            }
            Dbm e = z.copy();
            e.extrapolateLU(lower, upper);
            assertEquals(closure(lu), e, () -> "Extra+_LU of " + z);
            Dbm f = z.copy();
            f.extrapolateMaxBounds(max);
            assertEquals(closure(m), f, () -> "Extra_M of " + z);
            for (int i = 1; i < dim; i++) {
                boolean freed = true;
                for (int j = 0; j < dim; j++) {
                    freed &= i == j || e.upperBound(i, j) == Bound.INFINITY;
                }
                freedRows += freed ? 1 : 0;
            }
        }
        assertTrue(freedRows > 1000, "rows freed: " + freedRows);
    }

    /** A lower-bound or difference entry below {@code -max} weakened to {@code < -max}; {@code none} if no max. */
    private static int clamp(int b, int max, int none) {
        return max < 0 ? none : b < Bound.le(-max) ? Bound.lt(-max) : b;
    }

    /** The closure of a matrix of raw bounds whose diagonal is 0. */
    private static Dbm closure(int[][] matrix) {
        Dbm z = Dbm.unconstrained(matrix.length);
        for (int i = 0; i < matrix.length; i++) {
            for (int j = 0; j < matrix.length; j++) {
                if (i != j && matrix[i][j] != Bound.INFINITY) {
                    z.constrain(i, j, matrix[i][j]);
                }
            }
        }
        return z;
    }

    @Test
    void operationsKeepEmptyZonesEmpty() {
        Random r = new Random(16);
        for (int c = 0; c < 200; c++) {
            int dim = 2 + c % 4;
            Dbm z = Dbm.unconstrained(dim);
            z.constrain(0, 1, Bound.lt(-MAX_CONST));
            z.constrain(1, 0, Bound.le(MAX_CONST));
            assertTrue(z.isEmpty());
            Dbm canonicalEmpty = z.copy();
            for (int s = 0; s < 5; s++) {
                Zones.randomOperation(r, z, MAX_CONST);
            }
            z.extrapolateMaxBounds(randomMax(r, dim));
            assertFalse(z.intersect(Zones.randomZone(r, dim, MAX_CONST)));
            assertEquals(canonicalEmpty, z);
            assertFalse(z.satisfies(0, 1, Bound.INFINITY));
            assertFalse(z.contains(new long[dim], 1));
            assertTrue(z.isSubsetOf(Zones.randomZone(r, dim, MAX_CONST)));
            assertEquals("false", z.toString());
        }
    }
}
