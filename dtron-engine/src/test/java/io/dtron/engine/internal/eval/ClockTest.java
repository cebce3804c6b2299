package io.dtron.engine.internal.eval;

import static io.dtron.engine.internal.zone.Bound.le;
import static io.dtron.engine.internal.zone.Bound.lt;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import org.junit.jupiter.api.Test;

/** Clock resets, channel numbers, and guards and invariants applied to zones. */
class ClockTest {

    /** Clocks x = 1, y = 2, c[0..2] = 3..5. */
    private static final String CLOCKS = "clock x, y; clock c[3]; int n = 2; int i = 1;";

    /** A zone where time has passed from 0 and x - y lies in [0, 6]: every constraint below cuts something. */
    private static Dbm start() {
        Dbm z = Dbm.zero(6);
        z.up();
        z.constrain(1, 2, le(0));
        z.constrain(2, 1, le(0));
        z.reset(2, 0);
        z.up();
        z.constrain(1, 0, le(40_000));
        z.constrain(1, 2, le(6_000));
        return z;
    }

    @Test
    void updatesReportClockResetsInOrder() {
        TestModel m = TestModel.of(CLOCKS, "assign x = 0, c[i + 1] = 5, n = 7, y = n * 2;");
        m.run(0);
        assertEquals("1=0 5=5 2=14", m.resets());
        assertEquals(7, m.get("n"));
    }

    @Test
    void functionsResetClocksDirectlyAndThroughReferences() {
        TestModel m = TestModel.of(CLOCKS + """
                void spread(clock &cs[3], int base) { for (k : int[0,2]) cs[k] = base + k; }
                void one(clock &z) { z = 9; }
                void global() { x = n; }
                """, "assign spread(c, 10), one(c[i]), one(y), global();");
        m.run(0);
        assertEquals("3=10 4=11 5=12 4=9 2=9 1=2", m.resets());
        m.resets.clear();
        assertEquals(0, m.resets.size());
    }

    @Test
    void manyResetsAreAllKept() {
        TestModel m = TestModel.of(CLOCKS + " void count() { for (k : int[0,19]) c[k % 3] = k; }", "assign count();");
        m.run(0);
        assertEquals(20, m.resets.size());
        assertEquals(3 + 19 % 3, m.resets.clock(19));
        assertEquals(19, m.resets.value(19));
        assertEquals(17, m.resets.value(17));
        assertThrows(IndexOutOfBoundsException.class, () -> m.resets.value(20));
    }

    @Test
    void resetsApplyToZonesScaledToTicks() {
        TestModel m = TestModel.of(CLOCKS, "assign x = 3, y = 0, x = n;");
        m.run(0);
        Dbm zone = start();
        m.resets.applyTo(zone, 1000);
        Dbm expected = start();
        expected.reset(1, 3000);
        expected.reset(2, 0);
        expected.reset(1, 2000);
        assertEquals(expected, zone);
    }

    @Test
    void clockResetErrors() {
        TestModel m = TestModel.of(CLOCKS, "assign x = n - 5;", "assign c[i + 2] = 0;", "assign x = 2000000;");
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.run(0));
        assertEquals("a clock cannot be set to a negative value: 'x = n - 5' gives -3", e.getMessage());
        assertEquals("index 3 is out of range [0,2] of 'c'",
                assertThrows(ModelRuntimeException.class, () -> m.run(1)).getMessage());
        m.resets.clear();
        m.run(2);
        e = assertThrows(ModelRuntimeException.class, () -> m.resets.applyTo(start(), 1000));
        assertTrue(e.getMessage().startsWith("the clock value 2000000 is too large"), e.getMessage());
        assertEquals("x = 2000000", e.pos().text());
        assertThrows(IllegalArgumentException.class,
                () -> m.evaluator.evaluate(m.edge(2).updates().get(0), m.vars, null));
    }

    @Test
    void channelNumbersFollowArrayLayouts() {
        TestModel m = TestModel.of("chan a[3]; chan b[int[2,4]][2]; urgent chan u; int i = 1;",
                "sync a[i + 1]!;", "select j : int[2,4], k : int[0,1]; sync b[j][k]?;", "sync u!;",
                "sync a[i + 2]!;", "select j : int[2,4]; sync b[j][i]?;");
        assertEquals(2, channel(m, 0));
        for (int j = 2; j <= 4; j++) {
            for (int k = 0; k <= 1; k++) {
                int number = channel(m, 1, j, k);
                assertEquals(3 + (j - 2) * 2 + k, number);
                assertEquals("b[" + j + "][" + k + "]", m.network.channelName(number));
            }
        }
        assertEquals(m.network.channel("u").orElseThrow().index(), channel(m, 2));
        assertEquals("index 3 is out of range [0,2] of 'a'",
                assertThrows(ModelRuntimeException.class, () -> channel(m, 3)).getMessage());
        assertEquals("b[3][1]", m.network.channelName(channel(m, 4, 3)));
    }

    private static int channel(TestModel m, int edge, int... frame) {
        return m.evaluator.channel(m.edge(edge).sync().channel(), m.vars, frame);
    }

    /** Applies guard {@code k} of {@code m}, whose data conjuncts hold, to {@link #start()} (1000 ticks per unit). */
    private static Dbm constrained(TestModel m, int k, int... frame) {
        Dbm zone = start();
        boolean nonEmpty = m.evaluator.constrain(m.edge(k).guard(), m.vars, frame, zone, 1000);
        assertEquals(!zone.isEmpty(), nonEmpty);
        return zone;
    }

    /** {@link #start()} with the raw constraints {@code (i, j, bound)...}. */
    private static Dbm expected(int... triples) {
        Dbm zone = start();
        for (int k = 0; k < triples.length; k += 3) {
            zone.constrain(triples[k], triples[k + 1], triples[k + 2]);
        }
        return zone;
    }

    @Test
    void boundsOnOneClockInEitherOrder() {
        TestModel m = TestModel.guards(CLOCKS, "x < 5", "x <= 5", "x > 2", "x >= 2", "x == 3",
                "5 > x", "5 >= x", "2 < x", "2 <= x", "3 == x");
        assertEquals(expected(1, 0, lt(5000)), constrained(m, 0));
        assertEquals(expected(1, 0, le(5000)), constrained(m, 1));
        assertEquals(expected(0, 1, lt(-2000)), constrained(m, 2));
        assertEquals(expected(0, 1, le(-2000)), constrained(m, 3));
        assertEquals(expected(1, 0, le(3000), 0, 1, le(-3000)), constrained(m, 4));
        assertEquals(constrained(m, 0), constrained(m, 5));
        assertEquals(constrained(m, 1), constrained(m, 6));
        assertEquals(constrained(m, 2), constrained(m, 7));
        assertEquals(constrained(m, 3), constrained(m, 8));
        assertEquals(constrained(m, 4), constrained(m, 9));
        assertFalse(constrained(m, 0).equals(constrained(m, 1)), "strict and non-strict bounds differ");
    }

    @Test
    void differencesAndComparisonsOfTwoClocks() {
        TestModel m = TestModel.guards(CLOCKS, "x - y < 4", "x - y >= 2", "2 <= x - y", "4 > x - y",
                "x - y == 3", "x == y", "x < y", "y <= x", "c[i] - x > -1");
        assertEquals(expected(1, 2, lt(4000)), constrained(m, 0));
        assertEquals(expected(2, 1, le(-2000)), constrained(m, 1));
        assertEquals(constrained(m, 1), constrained(m, 2));
        assertEquals(constrained(m, 0), constrained(m, 3));
        assertEquals(expected(1, 2, le(3000), 2, 1, le(-3000)), constrained(m, 4));
        assertEquals(expected(1, 2, le(0), 2, 1, le(0)), constrained(m, 5));
        assertTrue(constrained(m, 6).isEmpty(), "x - y >= 0 holds everywhere in the start zone");
        assertEquals(expected(2, 1, le(0)), constrained(m, 7));
        assertEquals(expected(1, 4, lt(1000)), constrained(m, 8));
    }

    @Test
    void dataDependentBoundsConjunctionsAndFalseData() {
        TestModel m = TestModel.guards(CLOCKS, "x <= n * 2 && y > n - 1", "n > 100 && x < 3",
                "x >= 1 && n == 2 && y < 4 && x - y <= 1", "x > 5 && x < 3", "n == 2");
        assertEquals(expected(1, 0, le(4000), 0, 2, lt(-1000)), constrained(m, 0));
        Dbm zone = start();
        assertFalse(m.evaluator.constrain(m.edge(1).guard(), m.vars, null, zone, 1000));
        assertEquals(start(), zone);
        assertEquals(expected(0, 1, le(-1000), 2, 0, lt(4000), 1, 2, le(1000)), constrained(m, 2));
        assertTrue(constrained(m, 3).isEmpty());
        assertEquals(start(), constrained(m, 4));
        m.vars[m.variable("n").offset()] = 3;
        zone = start();
        assertFalse(m.evaluator.constrain(m.edge(4).guard(), m.vars, null, zone, 1000));
        assertEquals(start(), zone);
        assertEquals(expected(1, 0, le(6000), 0, 2, lt(-2000)), constrained(m, 0));
    }

    @Test
    void boundsAreScaledByTicksPerUnit() {
        TestModel m = TestModel.guards(CLOCKS, "x < 7 && y >= 1", "x < 2000000");
        for (int ticks : new int[] {1, 10, 1000}) {
            Dbm zone = Dbm.unconstrained(6);
            assertTrue(m.evaluator.constrain(m.edge(0).guard(), m.vars, null, zone, ticks));
            Dbm expected = Dbm.unconstrained(6);
            expected.constrain(1, 0, lt(7 * ticks));
            expected.constrain(0, 2, le(-ticks));
            assertEquals(expected, zone, "ticks " + ticks);
        }
        assertTrue(m.evaluator.constrain(m.edge(1).guard(), m.vars, null, Dbm.unconstrained(6), 1));
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class,
                () -> m.evaluator.constrain(m.edge(1).guard(), m.vars, null, Dbm.unconstrained(6), 1000));
        assertTrue(e.getMessage().contains("too large for the engine's time resolution"), e.getMessage());
    }

    @Test
    void selectBindingsIndexClocksInGuards() {
        TestModel m = TestModel.of(CLOCKS, "select k : int[0,2]; guard c[k] <= k + 1 && x - c[k] > 0;");
        Dbm zone = Dbm.unconstrained(6);
        assertTrue(m.evaluator.constrain(m.edge(0).guard(), m.vars, new int[] {2}, zone, 1));
        Dbm expected = Dbm.unconstrained(6);
        expected.constrain(5, 0, le(3));
        expected.constrain(5, 1, lt(0));
        assertEquals(expected, zone);
    }

    @Test
    void dataHoldsAndClockBoundsWithoutAZone() {
        TestModel m = TestModel.guards(CLOCKS, "x > 100 && n == 2 && x - y == 3", "y < 1 && n == 3");
        Expression g = m.edge(0).guard();
        assertTrue(m.evaluator.dataHolds(g, m.vars, null));
        assertFalse(m.evaluator.dataHolds(m.edge(1).guard(), m.vars, null));
        assertTrue(m.evaluator.dataHolds((io.dtron.model.Expression) null, m.vars, null));
        ClockBounds out = new ClockBounds();
        assertTrue(m.evaluator.clockBounds(g, m.vars, null, 10, out));
        assertEquals(3, out.size());
        assertEquals(0, out.i(0));
        assertEquals(1, out.j(0));
        assertEquals(lt(-1000), out.bound(0));
        assertEquals(1, out.i(1));
        assertEquals(2, out.j(1));
        assertEquals(le(30), out.bound(1));
        assertEquals(2, out.i(2));
        assertEquals(1, out.j(2));
        assertEquals(le(-30), out.bound(2));
        assertFalse(m.evaluator.clockBounds(m.edge(1).guard(), m.vars, null, 10, out));
        assertEquals(3, out.size());
        out.clear();
        assertEquals(0, out.size());
    }

    @Test
    void invariantsAndMissingGuards() {
        TestModel m = TestModel.load("""
                clock x, y; int n = 4;
                process P() { state A { x <= n && n > 0 }, B { y' == 0 && x <= 5 }, C { n < 0 }; init A;
                              trans A -> B {}; }
                system P;
                """);
        Location a = m.process("P").location("A");
        Dbm zone = Dbm.unconstrained(3);
        assertTrue(m.evaluator.constrain(a.invariant(), m.vars, new int[a.frameSize()], zone, 2));
        Dbm expected = Dbm.unconstrained(3);
        expected.constrain(1, 0, le(8));
        assertEquals(expected, zone);
        assertFalse(m.evaluator.constrain(m.process("P").location("C").invariant(), m.vars, null, zone, 2));
        assertEquals(expected, zone);
        assertTrue(m.evaluator.constrain(m.edge(0).guard(), m.vars, null, zone, 2));
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> m.evaluator.constrain(
                m.process("P").location("B").invariant(), m.vars, null, Dbm.unconstrained(3), 1));
        assertEquals("clock rates such as 'y' == 0' (stopwatches) are not supported by DTRON's engine",
                e.getMessage());
        assertThrows(IllegalArgumentException.class,
                () -> m.evaluator.evaluate(a.invariant(), m.vars, null));
    }
}
