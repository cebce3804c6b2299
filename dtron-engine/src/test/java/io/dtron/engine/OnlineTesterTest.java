package io.dtron.engine;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

class OnlineTesterTest {

    /** A ticker that must tick every 8..12 units, numbering its ticks; the environment may reset it. */
    static final String TICKER = """
            const int P = 10; const int T = 2;
            chan i_reset, o_tick;
            int[0,999] o_tick_seq;
            process Ticker() {
                clock x;
                state Running { x <= P + T };
                init Running;
                trans Running -> Running { guard x >= P - T; sync o_tick!; assign o_tick_seq = (o_tick_seq + 1) % 1000, x = 0; },
                      Running -> Running { sync i_reset?; assign x = 0, o_tick_seq = 0; };
            }
            process Env() {
                clock e;
                state Watching;
                init Watching;
                trans Watching -> Watching { guard e >= 25; sync i_reset!; assign e = 0; },
                      Watching -> Watching { sync o_tick?; };
            }
            system Ticker, Env;
            """;

    /** Ticks every {@code period} units; restarts on reset. */
    static final class Ticker implements Adapter {
        private final long period;
        private AdapterContext context;
        private TestClock.Scheduled next;
        private int seq;

        Ticker(long period) {
            this.period = period;
        }

        @Override
        public void start(AdapterContext context) {
            this.context = context;
            arm();
        }

        private void arm() {
            next = context.clock().schedule(period * context.timeUnitMicros(), () -> {
                seq = (seq + 1) % 1000;
                context.report(Event.of("tick", "seq", seq));
                arm();
            });
        }

        @Override
        public void perform(Event input) {
            next.cancel();
            seq = 0;
            arm();
        }
    }

    private static TestResult run(Adapter adapter, long seed, List<String> trace) throws Exception {
        Network n = ModelLoader.load("ticker.xta", TICKER);
        OnlineTester tester = new OnlineTester(n, TestInterface.fromNames(n), adapter,
                TestOptions.defaults(seed).withTimeout(500));
        tester.addListener(new TestListener() {
            @Override
            public void inputApplied(Event input, long micros) {
                trace.add(micros + " in " + input);
            }

            @Override
            public void outputObserved(Event output, long micros) {
                trace.add(micros + " out " + output);
            }
        });
        return tester.run();
    }

    @Test
    void aCorrectTickerPasses() throws Exception {
        List<String> trace = new ArrayList<>();
        TestResult r = run(new Ticker(10), 1, trace);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation() + "\n" + String.join("\n", trace));
        assertTrue(r.outputs() > 20, r.toString());
        assertTrue(r.inputs() > 0, r.toString());
    }

    @Test
    void aSlowTickerFails() throws Exception {
        List<String> trace = new ArrayList<>();
        TestResult r = run(new Ticker(13), 1, trace);
        assertEquals(Verdict.FAILED, r.verdict(), r.explanation() + "\n" + String.join("\n", trace));
        assertTrue(r.explanation().startsWith("no output came by t=12.000"), r.explanation());
    }

    @Test
    void realTimeRunsJudgeTheSameWay() throws Exception {
        Network n = ModelLoader.load("ticker.xta", TICKER);
        // 10 ms per unit: the model's 2-unit tolerance is 20 ms, wide enough for a loaded 2-core machine
        TestOptions realTime = TestOptions.defaults(3).withTimeout(40).withTimeUnit(10_000).withVirtualTime(false);
        long start = System.nanoTime();
        TestResult passed = new OnlineTester(n, TestInterface.fromNames(n), new Ticker(10), realTime).run();
        long took = (System.nanoTime() - start) / 1_000_000;
        assertEquals(Verdict.PASSED, passed.verdict(), passed.explanation());
        assertTrue(took >= 400, "40 units of 10 ms take at least 400 ms of real time, took " + took);
        assertTrue(passed.outputs() >= 3, passed.toString());
        TestResult failed = new OnlineTester(n, TestInterface.fromNames(n), new Ticker(13), realTime).run();
        assertEquals(Verdict.FAILED, failed.verdict(), failed.explanation());
    }

    @Test
    void listenersLearnWhatTheTesterWaitsForAndUntilWhen() throws Exception {
        Network n = ModelLoader.load("ticker.xta", TICKER);
        List<String> waits = new ArrayList<>();
        TestListener listener = new TestListener() {
            @Override
            public void waiting(long nowMicros, long untilMicros, Until until) {
                waits.add(nowMicros + " " + until + " " + untilMicros);
            }
        };
        TestOptions eager = TestOptions.defaults(5).withTimeout(300).withDelayPolicy(DelayPolicy.EAGER, 0);
        TestResult slow = new OnlineTester(n, TestInterface.fromNames(n), new Ticker(13), eager).addListener(listener)
                .run();
        assertEquals(Verdict.FAILED, slow.verdict(), slow.explanation());
        assertEquals("0 OUTPUT_DEADLINE 12000", waits.get(0), "the tick is due by t=12: " + waits);
        waits.clear();
        new OnlineTester(n, TestInterface.fromNames(n), new Ticker(10), eager.withTimeout(290)).addListener(listener)
                .run();
        assertTrue(waits.contains("20000 INPUT 25000"), "after the second tick, the reset at t=25: " + waits);
        assertEquals("285000 END 290000", waits.get(waits.size() - 1), "the tick due by t=297 is after the end: "
                + waits);
    }

    @Test
    void listenersLearnTheWindowInWhichEachOutputWasAllowed() throws Exception {
        // the model allows a tick 8 to 12 units after the last tick or reset; the run ends at t=500
        Network n = ModelLoader.load("ticker.xta", TICKER);
        List<long[]> windows = new ArrayList<>();
        List<String> order = new ArrayList<>();
        long[] last = {0};
        TestListener listener = new TestListener() {
            @Override
            public void inputApplied(Event input, long micros) {
                last[0] = micros;
                order.add("in");
            }

            @Override
            public void outputWindow(Event output, long micros, long earliestMicros, long latestMicros) {
                windows.add(new long[] {last[0], micros, earliestMicros, latestMicros});
                order.add("window");
            }

            @Override
            public void outputObserved(Event output, long micros) {
                last[0] = micros;
                order.add("out");
            }
        };
        TestResult r = new OnlineTester(n, TestInterface.fromNames(n), new Ticker(10),
                TestOptions.defaults(4).withTimeout(500)).addListener(listener).run();
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(r.outputs(), windows.size(), "a window for every output");
        for (long[] w : windows) {
            long latest = w[0] + 12_000 >= 500_000 ? -1 : w[0] + 12_000;
            assertEquals(List.of(w[0] + 8_000, latest), List.of(w[2], w[3]), "the tick at " + w[1] + " after "
                    + w[0]);
        }
        for (int i = 0; i < order.size(); i++) {
            assertEquals(order.get(i).equals("out"), i > 0 && order.get(i - 1).equals("window"), "order " + order);
        }
        // a ticker ticking after 7 units: too early; the window beside it is the one it missed, t=8 to 12
        windows.clear();
        last[0] = 0;
        TestResult early = new OnlineTester(n, TestInterface.fromNames(n), new Ticker(7),
                TestOptions.defaults(4).withTimeout(500)).addListener(listener).run();
        assertEquals(Verdict.FAILED, early.verdict(), early.explanation());
        assertEquals(1, windows.size());
        assertEquals(List.of(0L, 7_000L, 8_000L, 12_000L), List.of(windows.get(0)[0], windows.get(0)[1],
                windows.get(0)[2], windows.get(0)[3]));
    }

    @Test
    void delayPoliciesPlaceInputsAtTheStartOrTheEndOfTheirWindows() throws Exception {
        // the environment may reset from e >= 25 on, without an upper bound: eager resets at exactly 25
        Network n = ModelLoader.load("ticker.xta", TICKER);
        List<Long> resets = new ArrayList<>();
        new OnlineTester(n, TestInterface.fromNames(n), new Ticker(10),
                TestOptions.defaults(5).withTimeout(300).withDelayPolicy(DelayPolicy.EAGER, 0))
                .addListener(new TestListener() {
                    @Override
                    public void inputApplied(Event input, long micros) {
                        resets.add(micros);
                    }
                }).run();
        assertTrue(resets.size() >= 2, resets.toString());
        assertEquals(25_000L, resets.get(0));
        for (int i = 1; i < resets.size(); i++) {
            assertEquals(25_000L, resets.get(i) - resets.get(i - 1), resets.toString());
        }
        List<Long> bounded = new ArrayList<>();
        new OnlineTester(n, TestInterface.fromNames(n), new Ticker(10),
                TestOptions.defaults(5).withTimeout(300).withDelayPolicy(DelayPolicy.RANDOM_BOUNDED, 3))
                .addListener(new TestListener() {
                    @Override
                    public void inputApplied(Event input, long micros) {
                        bounded.add(micros);
                    }
                }).run();
        assertTrue(bounded.get(0) >= 25_000L && bounded.get(0) <= 28_000L, bounded.toString());
    }

    @Test
    void anOutputTheEnvironmentCannotAcceptIsInconclusive() throws Exception {
        // the implementation may beep at any time; the environment listens only once it has asked
        Network n = ModelLoader.load("beep.xta", """
                chan i_ask, o_beep;
                process Iut() { state A; init A; trans A -> A { sync o_beep!; }, A -> A { sync i_ask?; }; }
                process Env() { clock e; state Quiet { e <= 5 }, Listening; init Quiet;
                    trans Quiet -> Listening { guard e >= 5; sync i_ask!; }, Listening -> Listening { sync o_beep?; }; }
                system Iut, Env;
                """);
        Adapter beepsEarly = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.clock().schedule(2_000, () -> context.report(Event.of("beep")));
            }

            @Override
            public void perform(Event input) {
            }
        };
        TestResult r = new OnlineTester(n, TestInterface.fromNames(n), beepsEarly, TestOptions.defaults(1)).run();
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertTrue(r.explanation().startsWith("the environment model cannot accept output beep() at t=2.000: the"
                + " implementation may send it (Iut: A -> A), but no environment process can receive it in Env.Quiet"),
                r.explanation());
    }

    @Test
    void anOutputOfALateTaskComesAfterWhatTheTesterSawBeforeIt() throws Exception {
        // the system may say a or b at any time after go, which the eager tester sends at once
        Network n = ModelLoader.load("late.xta", """
                chan i_go, o_a, o_b;
                process Iut() { state S; init S; trans S -> S { sync i_go?; }, S -> S { sync o_a!; },
                    S -> S { sync o_b!; }; }
                process Env() { state Start, Done; init Start;
                    trans Start -> Done { sync i_go!; }, Done -> Done { sync o_a?; }, Done -> Done { sync o_b?; }; }
                system Iut, Env;
                """);
        // a is due at 5 ms, but the tester's thread is busy in perform until 30 ms; b comes at 10 ms meanwhile,
        // so the tester sees b before it runs the task that reports a
        Adapter busy = new Adapter() {
            private AdapterContext context;

            @Override
            public void start(AdapterContext context) {
                this.context = context;
                context.clock().schedule(5_000, () -> context.report(Event.of("a")));
            }

            @Override
            public void perform(Event input) {
                sleep(10);
                context.report(Event.of("b"));
                sleep(20);
            }
        };
        List<String> seen = new ArrayList<>();
        TestResult r = new OnlineTester(n, TestInterface.fromNames(n), busy,
                TestOptions.defaults(1).withTimeout(60).withVirtualTime(false).withDelayPolicy(DelayPolicy.EAGER, 0))
                .addListener(new TestListener() {
                    @Override
                    public void outputObserved(Event output, long micros) {
                        seen.add(output.channel() + "@" + micros);
                    }
                }).run();
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation() + " " + seen);
        assertEquals(2, r.outputs(), seen.toString());
        long bAt = Long.parseLong(seen.get(0).substring(2));
        assertEquals("b", seen.get(0).substring(0, 1), seen.toString());
        assertEquals("a@" + bAt, seen.get(1), "a, due at 5 ms, counts from b, seen before it: " + seen);
    }

    private static void sleep(long millis) {
        try {
            Thread.sleep(millis);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    @Test
    void anAdapterThatLosesItsSystemEndsTheRunInconclusive() throws Exception {
        Network n = ModelLoader.load("ticker.xta", TICKER);
        Adapter dropping = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.clock().schedule(5_000, () -> context.inconclusive("the connection to the ticker dropped"));
            }

            @Override
            public void perform(Event input) {
            }
        };
        TestResult r = new OnlineTester(n, TestInterface.fromNames(n), dropping, TestOptions.defaults(1)).run();
        assertEquals(Verdict.INCONCLUSIVE, r.verdict());
        assertEquals("the connection to the ticker dropped (at t=5.000)", r.explanation());
    }

    @Test
    void anOutputOutsideTheInterfaceIsInconclusive() throws Exception {
        Network n = ModelLoader.load("ticker.xta", TICKER);
        Adapter wrong = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.clock().schedule(9_000, () -> context.report(Event.of("tock", "seq", 1)));
            }

            @Override
            public void perform(Event input) {
            }
        };
        TestResult r = new OnlineTester(n, TestInterface.fromNames(n), wrong, TestOptions.defaults(1)).run();
        assertEquals(Verdict.INCONCLUSIVE, r.verdict());
        assertEquals("the adapter reported 'tock' at t=9.000, which is not an output of the model's interface",
                r.explanation());
    }

    @Test
    void aModelErrorWhileRunningIsReportedWithItsPlace() throws Exception {
        Network n = ModelLoader.load("overflow.xta", """
                chan i_go, o_done;
                int[0,3] n;
                process Iut() { state A; init A; trans A -> A { sync i_go?; assign n++; }, A -> A { guard n == 9; sync o_done!; }; }
                process Env() { state E; init E; trans E -> E { sync i_go!; }, E -> E { sync o_done?; }; }
                system Iut, Env;
                """);
        Adapter silent = new Adapter() {
            @Override
            public void start(AdapterContext context) {
            }

            @Override
            public void perform(Event input) {
            }
        };
        TestResult r = new OnlineTester(n, TestInterface.fromNames(n), silent,
                TestOptions.defaults(1).withDelayPolicy(DelayPolicy.EAGER, 0)).run();
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertTrue(r.explanation().startsWith("model error: overflow.xta:3:68: the value 4 is outside int[0,3] of 'n'"),
                r.explanation());
    }

    @Test
    void aProcessOnBothSidesIsRefusedWithTheReason() throws Exception {
        Network n = ModelLoader.load("both.xta", """
                chan i_go, o_done;
                process Confused() { state A; init A; trans A -> A { sync i_go!; }, A -> A { sync o_done!; }; }
                process Other() { state A; init A; trans A -> A { sync i_go?; }, A -> A { sync o_done?; }; }
                system Confused, Other;
                """);
        UnsupportedModelException e = org.junit.jupiter.api.Assertions.assertThrows(UnsupportedModelException.class,
                () -> new OnlineTester(n, TestInterface.fromNames(n), new Ticker(1), TestOptions.defaults(1)).run());
        assertTrue(e.getMessage().contains("process Confused sends output o_done but also sends input i_go"),
                e.getMessage());
    }

    @Test
    void aRunLongerThanTheEngineCanTimeIsRefusedWithTheLimit() {
        IllegalArgumentException timeout = org.junit.jupiter.api.Assertions.assertThrows(
                IllegalArgumentException.class, () -> new TestOptions(1, Long.MAX_VALUE, Integer.MAX_VALUE,
                        DelayPolicy.RANDOM, 0, true));
        assertEquals("the timeout of 2147483647 time units of 9223372036854775807 us is longer than DTRON can time: at"
                + " most 9223372036854775 us (about 292 years)", timeout.getMessage());
        IllegalArgumentException bound = org.junit.jupiter.api.Assertions.assertThrows(
                IllegalArgumentException.class, () -> new TestOptions(1, 1000, 1000, DelayPolicy.RANDOM_BOUNDED,
                        Long.MAX_VALUE / 1000, true));
        assertTrue(bound.getMessage().startsWith("the delay bound of "), bound.getMessage());
        TestOptions longest = new TestOptions(1, 1000, TestOptions.MAX_DURATION_MICROS / 1000, DelayPolicy.RANDOM, 0,
                true);
        assertTrue(TestOptions.fits(longest.timeout(), longest.timeUnitMicros()));
        assertTrue(!TestOptions.fits(longest.timeout() + 1, longest.timeUnitMicros()));
    }

    /** The environment may send go from e = 10 to e = 20; the system answers done one unit later. */
    static final String GO = """
            chan i_go, o_done;
            process Sys() {
                clock y;
                state Idle, Busy { y <= 1 };
                init Idle;
                trans Idle -> Busy { sync i_go?; assign y = 0; },
                      Busy -> Idle { guard y >= 1; sync o_done!; };
            }
            process Env() {
                clock e;
                state Waiting { e <= 20 }, Done;
                init Waiting;
                trans Waiting -> Done { guard e >= 10; sync i_go!; assign e = 0; },
                      Done -> Waiting { sync o_done?; assign e = 0; };
            }
            system Sys, Env;
            """;

    /** {@link #GO}'s system: answers done one unit after each go it applies. */
    private static class GoSystem implements Adapter {
        AdapterContext context;

        @Override
        public void start(AdapterContext context) {
            this.context = context;
        }

        @Override
        public void perform(Event input) {
            answer();
        }

        /** Reports done one unit from now. */
        void answer() {
            context.clock().schedule(context.timeUnitMicros(), () -> context.report(Event.of("done")));
        }
    }

    /** Runs {@link #GO} against {@code system}, adding the times the tester applied go at to {@code applied}. */
    private static TestResult runGo(Adapter system, TestOptions options, List<Long> applied) throws Exception {
        Network n = ModelLoader.load("go.xta", GO);
        return new OnlineTester(n, TestInterface.fromNames(n), system, options).addListener(new TestListener() {
            @Override
            public void inputApplied(Event input, long micros) {
                applied.add(micros);
            }
        }).run();
    }

    /** When go was applied, in each run with an adapter whose inputs on go take {@code delayUnits} to arrive. */
    private static List<Long> goTimes(long delayUnits, DelayPolicy policy) throws Exception {
        List<Long> applied = new ArrayList<>();
        Adapter delayed = new GoSystem() {
            @Override
            public long inputDelayMicros(String channel) {
                assertEquals("go", channel);
                return delayUnits * context.timeUnitMicros();
            }
        };
        TestResult r = runGo(delayed, TestOptions.defaults(3).withTimeout(100).withDelayPolicy(policy, 0), applied);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        return applied;
    }

    @Test
    void anInputLeavesRoomForItsChannelsDelayBeforeItsWindowCloses() throws Exception {
        // lazy: as late as the delay allows, 20 - 3 units after the window of 10..20 opened
        List<Long> lazy = goTimes(3, DelayPolicy.LAZY);
        assertTrue(lazy.size() >= 2, lazy.toString());
        assertEquals(17_000L, lazy.get(0));
        assertEquals(17_000L + 1_000 + 17_000, lazy.get(1), lazy.toString());
        // random: never later than the room allows
        for (long at : goTimes(3, DelayPolicy.RANDOM).subList(0, 1)) {
            assertTrue(at >= 10_000 && at <= 17_000, "go at " + at);
        }
        // a window (10 units) narrower than the room (15 units): the earliest point, the window's start
        assertEquals(10_000L, goTimes(15, DelayPolicy.LAZY).get(0));
        assertEquals(10_000L, goTimes(15, DelayPolicy.RANDOM).get(0));
    }

    @Test
    void anOutputStampedAfterAnInputTheTesterMissedIsInconclusiveNotFailed() throws Exception {
        // go must come by e = 20; an output stamped at 23 (its stamp ran ahead of the tester's clock, or the tester
        // was held up) comes after the tester missed its input: it cannot be judged, whatever the output
        Network n = ModelLoader.load("go.xta", GO);
        Adapter ahead = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.report(Event.of("done"), 23 * context.timeUnitMicros(), 0);
            }

            @Override
            public void perform(Event input) {
            }
        };
        TestResult r = new OnlineTester(n, TestInterface.fromNames(n), ahead,
                TestOptions.defaults(3).withTimeout(100)).run();
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertTrue(r.explanation().startsWith("output done() observed at t=23.000 may have come after t=20.000, when"
                + " the environment's window for an input closed, and the tester had applied none by then (input"
                + " executed too late). The model allowed these inputs: go between t=10.000 and t=20.000"),
                r.explanation());
    }

    @Test
    void anInputToAnAdapterThatHoldsItIsPerformedAheadAndPlacedAtItsTime() throws Exception {
        // the adapter holds go until its time (a lead of 4 units), applies it then and answers done a unit later
        List<long[]> performed = new ArrayList<>();
        List<Long> applied = new ArrayList<>();
        Adapter holding = new GoSystem() {
            private long ordinal;

            @Override
            public void perform(Event input) {
                throw new AssertionError("go is performed ahead of its time, never at it");
            }

            @Override
            public void perform(Event input, long dueMicros) {
                long number = ++ordinal;
                performed.add(new long[] {context.clock().nowMicros(), dueMicros});
                context.clock().schedule(dueMicros - context.clock().nowMicros(), () -> {
                    context.inputApplied(number, dueMicros);
                    answer();
                });
            }

            @Override
            public long inputLeadMicros(String channel) {
                return 4 * context.timeUnitMicros();
            }

            @Override
            public boolean acknowledgesInputs() {
                return true;
            }
        };
        TestResult r = runGo(holding, TestOptions.defaults(5).withTimeout(200).withReorderWindow(2_000), applied);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertTrue(performed.size() >= 2, r.explanation());
        for (int i = 0; i < performed.size(); i++) {
            long at = performed.get(i)[0];
            long due = performed.get(i)[1];
            // performed 4 units ahead (or at once, when the window opens sooner), placed at its time
            assertTrue(due > at && due - at <= 4_000, "performed at " + at + ", due at " + due);
            assertEquals(due, applied.get(i));
        }
        // each due inside its window: 10 to 20 units after the last done (after time 0 for the first)
        assertTrue(performed.get(0)[1] >= 10_000 && performed.get(0)[1] <= 20_000, "first due " + performed.get(0)[1]);
    }

    @Test
    void withoutAReorderWindowNoInputIsPerformedAhead() throws Exception {
        // an output stamped before an input performed ahead could not be placed before it: inputs go at their time
        Adapter holding = new GoSystem() {
            @Override
            public void perform(Event input, long dueMicros) {
                throw new AssertionError("performed ahead without a reorder window");
            }

            @Override
            public long inputLeadMicros(String channel) {
                return 4 * context.timeUnitMicros();
            }
        };
        TestResult r = runGo(holding, TestOptions.defaults(5).withTimeout(100), new ArrayList<>());
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertTrue(r.inputs() >= 2, r.explanation());
    }
}
