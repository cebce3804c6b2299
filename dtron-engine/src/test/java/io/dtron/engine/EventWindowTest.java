package io.dtron.engine;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.monitor.Alarm;
import io.dtron.engine.monitor.Monitor;
import io.dtron.engine.monitor.MonitorOptions;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The tester keeps when in an event's window the event came: a time known give or take a clock error holds for the
 * events after it too, and a time between two ticks adds no rounding from event to event. Virtual time.
 */
class EventWindowTest {
    /** Output two exactly 10 units after output one. */
    private static final String EXACTLY_TEN = """
            chan o_one, o_two;
            process Sut() {
                clock x;
                state A, B, C;
                init A;
                trans A -> B { sync o_one!; assign x = 0; },
                      B -> C { guard x == 10; sync o_two!; };
            }
            process Env() {
                state E;
                init E;
                trans E -> E { sync o_one?; }, E -> E { sync o_two?; };
            }
            system Sut, Env;
            """;

    /** Output tick every 10 units exactly, the first at 10. */
    private static final String PERIOD_TEN = """
            chan o_tick;
            process Sut() {
                clock x;
                state A { x <= 10 };
                init A;
                trans A -> A { guard x == 10; sync o_tick!; assign x = 0; };
            }
            process Env() {
                state E;
                init E;
                trans E -> E { sync o_tick?; };
            }
            system Sut, Env;
            """;

    /** A system that reports its outputs: each at its stamp, give or take an error, a tenth of a unit later. */
    private record Stamped(long unit, long errorMicros, List<String> channels, double... stamps) implements Adapter {
        @Override
        public void start(AdapterContext context) {
            for (int i = 0; i < stamps.length; i++) {
                long at = Math.round(stamps[i] * unit);
                Event e = Event.of(channels.get(Math.min(i, channels.size() - 1)));
                context.clock().schedule(at + unit / 10, () -> context.report(e, at, errorMicros));
            }
        }

        @Override
        public void perform(Event input) {
        }
    }

    private static TestResult run(String model, long unit, int timeout, Adapter adapter) throws Exception {
        Network n = ModelLoader.load("model.xta", model);
        // the reorder window lets an output reported after a deadline be judged at its stamp
        TestOptions options = TestOptions.defaults(1).withTimeUnit(unit).withTimeout(timeout).withReorderWindow(unit);
        return new OnlineTester(n, TestInterface.fromNames(n), adapter, options).run();
    }

    @Test
    void anEventGiveOrTakeHoldsForTheEventsAfterIt() throws Exception {
        // one truly at 3, stamped 3.5; two truly at 13, stamped 12.5; both give or take 0.5: exactly 10 apart is
        // within the windows only when one's window is kept after it (from one's stamp two is 9 +- 1 later)
        TestResult r = run(EXACTLY_TEN, 1000, 20, new Stamped(1000, 500, List.of("one", "two"), 3.5, 12.5));
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(2, r.outputs(), r.toString());
    }

    @Test
    void eventsTooFarApartForTheirWindowsStillFail() throws Exception {
        // two at least 14.5 - 3.5 = 11 units after one
        TestResult r = run(EXACTLY_TEN, 1000, 20, new Stamped(1000, 500, List.of("one", "two"), 3, 15));
        assertEquals(Verdict.FAILED, r.verdict(), r.explanation());
        assertTrue(r.explanation().contains("output two() observed at t=15.000 is not allowed then"), r.explanation());
    }

    @Test
    void manyEventsEachGiveOrTakeFitThePeriod() throws Exception {
        // truly every 10 units, the stamps 0.4 late and early in turn, give or take 0.5
        TestResult r = run(PERIOD_TEN, 1000, 75, new Stamped(1000, 500, List.of("tick"),
                10.4, 19.6, 30.4, 39.6, 50.4, 59.6, 70.4));
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(7, r.outputs(), r.toString());
    }

    @Test
    void errorsThatAddUpOverManyEventsFail() throws Exception {
        // every 10.4 units: each step fits 10 give or take the two windows, but the first must be at 10, and the
        // second, stamped 20.8 give or take 0.5, cannot be at 20
        TestResult r = run(PERIOD_TEN, 1000, 75, new Stamped(1000, 500, List.of("tick"), 10.4, 20.8, 31.2));
        assertEquals(Verdict.FAILED, r.verdict(), r.explanation());
        assertTrue(r.explanation().contains("observed at t=20.800"), r.explanation());
    }

    /**
     * Input go when the environment's clock reaches 5 units; the system answers with a at any time. The clock is
     * reset only by go, so a's at times between two ticks must not move it.
     */
    private static final String EAGER = """
            chan i_go, o_a;
            process Sut() {
                state S;
                init S;
                trans S -> S { sync i_go?; }, S -> S { sync o_a!; };
            }
            process Env() {
                clock e;
                state E;
                init E;
                trans E -> E { guard e >= 5; sync i_go!; assign e = 0; }, E -> E { sync o_a?; };
            }
            system Sut, Env;
            """;

    /** Three a's after each go, 0.3337, 1.4441 and 3.7773 units after it: between the ticks of a millisecond. */
    private record Answering(long unit, List<Object[]> trace, AdapterContext[] context)
            implements Adapter, TestListener {
        Answering(long unit) {
            this(unit, new ArrayList<>(), new AdapterContext[1]);
        }

        @Override
        public void start(AdapterContext started) {
            context[0] = started;
        }

        @Override
        public void perform(Event input) {
            AdapterContext c = context[0];
            long now = c.clock().nowMicros();
            for (double after : new double[] {0.3337, 1.4441, 3.7773}) {
                long delay = Math.round(after * unit);
                c.clock().schedule(delay, () -> c.report(Event.of("a"), now + delay));
            }
        }

        @Override
        public void inputApplied(Event input, long micros) {
            trace.add(new Object[] {input, micros});
        }

        @Override
        public void outputObserved(Event output, long micros) {
            trace.add(new Object[] {output, micros});
        }
    }

    @Test
    void eagerInputsKeepTheBoundByTheStampsAndTheMonitorAgrees() throws Exception {
        long unit = 1_000_000; // a tick is a millisecond; the outputs come between ticks
        Network n = ModelLoader.load("model.xta", EAGER);
        TestInterface ti = TestInterface.fromNames(n);
        Answering sut = new Answering(unit);
        TestOptions options = TestOptions.defaults(7).withTimeUnit(unit).withTimeout(400)
                .withDelayPolicy(DelayPolicy.EAGER, 0);
        TestResult r = new OnlineTester(n, ti, sut, options).addListener(sut).run();
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertTrue(r.inputs() >= 70, r.toString());
        // replayed by a monitor with no tolerance: no violation
        Monitor monitor = Monitor.of(n, ti, MonitorOptions.initial(unit));
        for (Object[] e : sut.trace()) {
            Alarm alarm = monitor.observe((Event) e[0], (long) e[1]);
            assertNull(alarm, () -> alarm.explanation());
        }
        assertEquals(sut.trace().size(), monitor.events());
        assertEquals(r.inputs() + r.outputs(), sut.trace().size());
        long lastInput = 0;
        for (Object[] e : sut.trace()) {
            if (((Event) e[0]).channel().equals("go")) {
                // by the stamps, every go at least 5 units after the last: the environment's guard
                assertTrue((long) e[1] - lastInput >= 5 * unit, "go at " + e[1] + " after " + lastInput);
                lastInput = (long) e[1];
            }
        }
    }

    @Test
    void theMonitorKeepsTheTicksOfItsStart() throws Exception {
        long unit = 1_000_000;
        Network n = ModelLoader.load("model.xta", EAGER);
        TestInterface ti = TestInterface.fromNames(n);
        for (long second : new long[] {10_000_000, 9_998_300}) {
            Monitor monitor = Monitor.of(n, ti, MonitorOptions.initial(unit));
            assertNull(monitor.observe(Event.of("go"), 5_000_000));
            for (long a : new long[] {5_333_700, 6_444_100, 8_777_300}) {
                assertNull(monitor.observe(Event.of("a"), a));
            }
            // three a's between the ticks move the clock of go by no tick: 1.7 ms early is early
            Alarm alarm = monitor.observe(Event.of("go"), second);
            assertEquals(second < 10_000_000, alarm != null, () -> second + ": " + alarm);
        }
    }
}
