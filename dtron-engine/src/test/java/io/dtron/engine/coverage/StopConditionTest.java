package io.dtron.engine.coverage;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.Network;
import java.util.Map;
import java.util.function.BooleanSupplier;
import org.junit.jupiter.api.Test;

/**
 * GraphWalker #341's combination {@code (location_coverage(100) and reached(1)) or time(90)}, each branch, on
 * press.xta in virtual time (one model time unit is 1000 us), and the errors of bad expressions.
 */
class StopConditionTest {
    private static final String GW341 = "(location_coverage(100) and reached(1)) or time(90)";
    private static final long UNIT = 1000;

    /** One goal, reached when {@code reached} says so, read on the tester's thread. */
    private static Goals goal(BooleanSupplier reached) {
        return new Goals() {
            @Override
            public int count() {
                return 1;
            }

            @Override
            public boolean reached(int goal) {
                return reached.getAsBoolean();
            }
        };
    }

    /** Runs press.xta with the user's presses every {@code wait} units, goal 1 being Lamp.On visited or not. */
    private static TestResult run(String until, int wait, long timeout, boolean goalIsOn) throws Exception {
        Network n = CoverageTest.model("press.xta", Map.of("const int WAIT = 3;", "const int WAIT = " + wait + ";"));
        // inputs as early as the user allows them: the first press at t=WAIT
        OnlineTester t = new OnlineTester(n, io.dtron.model.TestInterface.fromNames(n), new CoverageTest.PressLamp(),
                io.dtron.engine.TestOptions.defaults(7).withTimeout(timeout)
                        .withDelayPolicy(io.dtron.engine.DelayPolicy.EAGER, 0));
        int lamp = n.process("Lamp").orElseThrow().index();
        int on = n.process("Lamp").orElseThrow().location("On").index();
        int broken = n.process("Lamp").orElseThrow().location("Broken").index();
        t.until(StopCondition.parse(until), goal(() -> t.coverage().locationVisited(lamp, goalIsOn ? on : broken)));
        return t.run();
    }

    @Test
    void bothCoverageAndTheGoalStopTheRunWhenTheyHoldTogether() throws Exception {
        TestResult r = run(GW341, 3, 1000, true);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        // every reachable location is visited, and the goal reached, when on comes: one unit after the first press
        Coverage c = r.coverage();
        assertEquals(new Coverage.Figure(4, 4), c.locations());
        assertEquals(1, r.outputs());
        assertEquals(1, r.inputs());
        assertEquals(4 * UNIT, r.durationMicros());
        assertEquals("the stop condition " + GW341 + " was met at t=4.000"
                + " by location_coverage(100) and reached(1), after 1 inputs and 1 outputs, all as the model allows",
                r.explanation());
    }

    @Test
    void coverageWithoutTheGoalRunsToTime90() throws Exception {
        TestResult r = run(GW341, 3, 1000, false);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(new Coverage.Figure(4, 4), r.coverage().locations());
        assertEquals(90 * UNIT, r.durationMicros());
        assertTrue(r.explanation().startsWith("the stop condition " + GW341 + " was met at t=90.000"
                + " by time(90),"), r.explanation());
    }

    @Test
    void theGoalWithoutCoverageRunsToTime90() throws Exception {
        // the user presses after 100 units only: Dimming and On are not visited by 90, Lamp.Off (the goal) is
        TestResult r = run("(location_coverage(100) and reached(1)) or time(90)", 100, 1000, true);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(new Coverage.Figure(2, 4), r.coverage().locations());
        assertEquals(0, r.inputs());
        assertEquals(90 * UNIT, r.durationMicros());
        assertTrue(r.explanation().contains("by time(90),"), r.explanation());
    }

    @Test
    void neitherRunsToTime90() throws Exception {
        TestResult r = run(GW341, 100, 1000, false);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(90 * UNIT, r.durationMicros());
        assertTrue(r.explanation().contains("by time(90),"), r.explanation());
    }

    @Test
    void theTimeoutStaysTheOuterBound() throws Exception {
        TestResult r = run(GW341, 100, 50, false);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(50 * UNIT, r.durationMicros());
        assertTrue(r.explanation().startsWith("the timeout of 50 time units was reached"), r.explanation());
    }

    @Test
    void andBindsTighterThanOr() throws Exception {
        // inputs(1) or inputs(5) and time(1000): the first press stops the run
        TestResult r = run("inputs(1) or inputs(5) and time(1000)", 3, 1000, false);
        assertEquals(1, r.inputs());
        assertTrue(r.explanation().contains("by inputs(1),"), r.explanation());
    }

    @Test
    void badExpressionsSayWhereAndWhy() {
        assertEquals("column 23: expected a condition, found the end", error("edge_coverage(100) and"));
        assertEquals("column 1: unknown condition 'coverage': use edge_coverage(P), location_coverage(P),"
                + " trap_coverage(P), reached(N), time(T) or inputs(N)", error("coverage(100)"));
        assertEquals("column 15: edge_coverage takes a percentage from 0 to 100, not 101", error("edge_coverage(101)"));
        assertEquals("column 9: reached takes a whole number from 1, not 0", error("reached(0)"));
        assertEquals("column 9: expected ')', found the end", error("(time(5)"));
        assertEquals("column 6: expected a number in time(...)", error("time(x)"));
        assertEquals("column 9: expected 'and', 'or' or the end, found 'time(2)'", error("time(1) time(2)"));
        assertEquals("column 6: time takes a whole number, not 1.5", error("time(1.5)"));
    }

    @Test
    void conditionsThatDoNotFitTheRunAreRefusedBeforeIt() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> StopCondition.parse("time(5) or reached(2)").check(1, 2));
        assertEquals("column 12: reached(2) asks for goal 2, but the run has 1 goal", e.getMessage());
        e = assertThrows(IllegalArgumentException.class, () -> StopCondition.parse("trap_coverage(50)").check(0, 0));
        assertEquals("column 1: trap_coverage asks about traps, but the model has none (bool variables or arrays"
                + " named trap... or t_..., or named with --traps)", e.getMessage());
    }

    private static String error(String text) {
        return assertThrows(IllegalArgumentException.class, () -> StopCondition.parse(text)).getMessage();
    }
}
