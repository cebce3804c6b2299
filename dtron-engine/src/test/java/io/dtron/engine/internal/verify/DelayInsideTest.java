package io.dtron.engine.internal.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import org.junit.jupiter.api.Test;

/**
 * The delays that stay inside a union of zones, against a brute force on a grid: with two clocks and integer
 * constants, every point where a line of delay crosses a bound is a multiple of 1/8 away from a point of the
 * 1/8 grid, so sampling the delays in steps of 1/16 sees every piece of every line.
 */
class DelayInsideTest {
    private static final int DIM = 3;
    private static final long DEN = 16;

    @Test
    void theDelaysInsideAUnionOfZonesAreExactlyThoseOfTheBruteForce() {
        Random random = new Random(16);
        int nonTrivial = 0;
        for (int round = 0; round < 600; round++) {
            Dbm entry = randomZone(random, 4);
            if (entry.isEmpty()) {
                continue;
            }
            Dbm closure = entry.copy();
            closure.up();
            closure.constrain(1, 0, Bound.le(8));
            List<Dbm> in = new ArrayList<>();
            for (int k = 0; k < 1 + random.nextInt(3); k++) {
                Dbm z = randomZone(random, 8);
                if (z.intersect(closure)) {
                    in.add(z);
                }
            }
            if (in.isEmpty()) {
                continue;
            }
            List<Dbm> result = Checker.delayInside(entry, closure, in);
            boolean someIn = false;
            boolean someOut = false;
            for (long x = 0; x <= 10 * 8; x++) {
                for (long y = 0; y <= 10 * 8; y++) {
                    long[] w = {0, 2 * x, 2 * y};
                    if (!closure.contains(w, DEN)) {
                        continue;
                    }
                    boolean expected = reachable(entry, in, w);
                    boolean actual = result.stream().anyMatch(z -> z.contains(w, DEN));
                    assertEquals(expected, actual, "round " + round + ": entry " + entry + ", in " + in + ", point ("
                            + x / 8.0 + ", " + y / 8.0 + ")");
                    someIn |= actual;
                    someOut |= !actual && in.stream().anyMatch(z -> z.contains(w, DEN));
                }
            }
            if (someIn && someOut) {
                nonTrivial++;
            }
        }
        assertTrue(nonTrivial > 20, "cases where the property holds at a point but no delay inside it gets there: "
                + nonTrivial);
    }

    /** Whether some point of {@code entry} reaches {@code w} by a delay that stays in the union {@code in}. */
    private static boolean reachable(Dbm entry, List<Dbm> in, long[] w) {
        // the shortest delay from entry is the best one; delays are sampled in steps of 1/16
        for (long d = 0; d <= Math.min(w[1], w[2]); d++) {
            long[] v = {0, w[1] - d, w[2] - d};
            if (entry.contains(v, DEN)) {
                for (long e = 0; e <= d; e++) {
                    long[] u = {0, v[1] + e, v[2] + e};
                    if (in.stream().noneMatch(z -> z.contains(u, DEN))) {
                        return false;
                    }
                }
                return true;
            }
        }
        return false;
    }

    /** A zone of two clocks with random integer bounds up to {@code max}, strict or not (maybe empty). */
    private static Dbm randomZone(Random random, int max) {
        Dbm z = Dbm.unconstrained(DIM);
        for (int k = 0; k < 2 + random.nextInt(3); k++) {
            int i = random.nextInt(DIM);
            int j = random.nextInt(DIM);
            if (i == j) {
                continue;
            }
            int c = random.nextInt(max + 1) - (i == 0 ? max : j == 0 ? 0 : max / 2);
            z.constrain(i, j, Bound.of(c, random.nextBoolean()));
        }
        return z;
    }
}
