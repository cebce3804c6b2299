package io.dtron.engine.internal.zone;

import static io.dtron.engine.internal.zone.Bound.INFINITY;
import static io.dtron.engine.internal.zone.Bound.MAX_VALUE;
import static io.dtron.engine.internal.zone.Bound.add;
import static io.dtron.engine.internal.zone.Bound.le;
import static io.dtron.engine.internal.zone.Bound.lt;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;
import org.junit.jupiter.api.Test;

class BoundTest {

    @Test
    void encodesValueAndStrictness() {
        assertEquals(10, Bound.of(5, true));
        assertEquals(11, Bound.of(5, false));
        assertEquals(-6, lt(-3));
        assertEquals(-5, le(-3));
        assertEquals(Bound.LE_ZERO, le(0));
        assertEquals(Bound.LT_ZERO, lt(0));
        for (int v : new int[] {0, 1, -1, 7, -7, 1 << 29, -(1 << 29), MAX_VALUE, -MAX_VALUE}) {
            assertEquals(v, Bound.value(lt(v)));
            assertEquals(v, Bound.value(le(v)));
            assertTrue(Bound.isStrict(lt(v)));
            assertFalse(Bound.isStrict(le(v)));
            assertFalse(Bound.isInfinite(le(v)));
        }
    }

    @Test
    void infinityIsStrictAndAboveEveryFiniteBound() {
        assertTrue(Bound.isInfinite(INFINITY));
        assertTrue(Bound.isStrict(INFINITY));
        assertTrue(le(MAX_VALUE) < INFINITY);
        assertTrue(Bound.compare(le(MAX_VALUE), INFINITY) < 0);
        assertThrows(IllegalArgumentException.class, () -> Bound.value(INFINITY));
    }

    @Test
    void rejectsValuesOutOfRange() {
        assertThrows(IllegalArgumentException.class, () -> le(MAX_VALUE + 1));
        assertThrows(IllegalArgumentException.class, () -> lt(-MAX_VALUE - 1));
        assertThrows(IllegalArgumentException.class, () -> Bound.of(Integer.MIN_VALUE, true));
    }

    @Test
    void orderIsTightness() {
        assertTrue(Bound.compare(lt(5), le(5)) < 0);
        assertTrue(Bound.compare(le(5), lt(6)) < 0);
        assertTrue(Bound.compare(le(-6), lt(-5)) < 0);
        assertEquals(0, Bound.compare(le(4), le(4)));
        assertTrue(Bound.compare(le(5), lt(5)) > 0);
        assertEquals(lt(5), Math.min(le(5), lt(5)));
    }

    @Test
    void addsValuesAndStrictness() {
        assertEquals(le(5), add(le(2), le(3)));
        assertEquals(lt(5), add(lt(2), le(3)));
        assertEquals(lt(5), add(le(2), lt(3)));
        assertEquals(lt(5), add(lt(2), lt(3)));
        assertEquals(lt(3), add(le(-2), lt(5)));
        assertEquals(le(-9), add(le(-4), le(-5)));
        assertEquals(INFINITY, add(INFINITY, le(-5)));
        assertEquals(INFINITY, add(lt(3), INFINITY));
    }

    @Test
    void addAgreesWithTheSemanticsOfSums() {
        Random r = new Random(42);
        for (int k = 0; k < 10_000; k++) {
            int a = r.nextInt(2001) - 1000;
            int b = r.nextInt(2001) - 1000;
            boolean sa = r.nextBoolean();
            boolean sb = r.nextBoolean();
            int sum = add(Bound.of(a, sa), Bound.of(b, sb));
            assertEquals(a + b, Bound.value(sum));
            assertEquals(sa || sb, Bound.isStrict(sum));
            assertEquals(sum, add(Bound.of(b, sb), Bound.of(a, sa)));
        }
    }

    @Test
    void addNeverOverflows() {
        assertEquals(le(MAX_VALUE), add(le(MAX_VALUE), le(0)));
        assertEquals(INFINITY, add(le(MAX_VALUE), le(1)));
        assertEquals(INFINITY, add(le(MAX_VALUE), le(MAX_VALUE)));
        assertEquals(le(MAX_VALUE), add(le(1 << 29), le(MAX_VALUE - (1 << 29))));
        assertEquals(le(-MAX_VALUE), add(le(-(1 << 29)), le(-MAX_VALUE + (1 << 29))));
        // Below the range the sum is clamped to the weakest bound there, "< -MAX_VALUE".
        assertEquals(lt(-MAX_VALUE), add(le(-MAX_VALUE), le(-1)));
        assertEquals(lt(-MAX_VALUE), add(lt(-MAX_VALUE), lt(-MAX_VALUE)));
        assertEquals(le(0), add(le(MAX_VALUE), le(-MAX_VALUE)));
    }

    @Test
    void printsBounds() {
        assertEquals("<5", Bound.toString(lt(5)));
        assertEquals("<=5", Bound.toString(le(5)));
        assertEquals("<=-2", Bound.toString(le(-2)));
        assertEquals("<0", Bound.toString(Bound.LT_ZERO));
        assertEquals("<inf", Bound.toString(INFINITY));
    }
}
