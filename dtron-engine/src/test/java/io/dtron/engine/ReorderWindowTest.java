package io.dtron.engine;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import org.junit.jupiter.api.Test;

/**
 * Observations placed by their own times within the reorder window: a message that crossed another on its way to
 * the tester is judged in its true place, and delays beyond the window end the run INCONCLUSIVE, never FAILED.
 * Virtual time, 1000 us per unit.
 */
class ReorderWindowTest {
    private static final long UNIT = 1000;

    /** Output x is allowed only before input y, which the environment sends at t=10 (and by t=LATEST). */
    private static final String CROSSING = """
            chan i_y, o_x;
            process Sut() {
                state Waiting, Got, Over;
                init Waiting;
                trans Waiting -> Got { sync o_x!; },
                      Waiting -> Over { sync i_y?; },
                      Got -> Over { sync i_y?; };
            }
            process Env() {
                clock e;
                state Start { e <= LATEST }, Sent;
                init Start;
                trans Start -> Start { sync o_x?; },
                      Start -> Sent { guard e >= 10; sync i_y!; },
                      Sent -> Sent { sync o_x?; };
            }
            system Sut, Env;
            """;

    private static String crossing(int latest) {
        return CROSSING.replace("LATEST", Integer.toString(latest));
    }

    /** Output x must come by t=5. */
    private static final String DEADLINE = """
            chan o_x;
            process Sut() {
                clock c;
                state Waiting { c <= 5 }, Done;
                init Waiting;
                trans Waiting -> Done { sync o_x!; };
            }
            process Env() {
                state Watching;
                init Watching;
                trans Watching -> Watching { sync o_x?; };
            }
            system Sut, Env;
            """;

    /**
     * A system whose adapter reports output x, that happened at {@code happened} units, when the run's clock reads
     * {@code arrives} units; and, if {@code appliedAt} is positive, acknowledges the first input as applied then.
     */
    private static class Delayed implements Adapter {
        private final double happened;
        private final double arrives;
        private final double appliedAt;
        private AdapterContext context;

        Delayed(double happened, double arrives, double appliedAt) {
            this.happened = happened;
            this.arrives = arrives;
            this.appliedAt = appliedAt;
        }

        @Override
        public void start(AdapterContext context) {
            this.context = context;
            context.clock().schedule(micros(arrives), () -> context.report(Event.of("x"), micros(happened)));
        }

        @Override
        public void perform(Event input) {
            if (appliedAt > 0) {
                long now = context.clock().nowMicros();
                context.clock().schedule(micros(appliedAt) - now, () -> context.inputApplied(1, micros(appliedAt)));
            }
        }
    }

    private static long micros(double units) {
        return Math.round(units * UNIT);
    }

    private static TestResult run(String model, Adapter adapter, double windowUnits) throws Exception {
        Network n = ModelLoader.load("model.xta", model);
        TestOptions options = TestOptions.defaults(1).withTimeout(20).withDelayPolicy(DelayPolicy.EAGER, 0)
                .withReorderWindow(micros(windowUnits));
        return new OnlineTester(n, TestInterface.fromNames(n), adapter, options).run();
    }

    @Test
    void anOutputThatCrossedAnInputIsJudgedWhereItHappened() throws Exception {
        // x happened at 9.5, before y at 10, but reached the tester at 10.5
        TestResult r = run(crossing(10), new Delayed(9.5, 10.5, 0), 2);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(1, r.outputs(), r.toString());
        assertEquals(1, r.inputs(), r.toString());
    }

    @Test
    void withoutAWindowTheSameCrossingFails() throws Exception {
        TestResult r = run(crossing(10), new Delayed(9.5, 10.5, 0), 0);
        assertEquals(Verdict.FAILED, r.verdict(), r.explanation());
    }

    @Test
    void anOutputTrulyAfterTheInputFailsAfterTheWindow() throws Exception {
        TestResult r = run(crossing(10), new Delayed(10.5, 10.6, 0), 2);
        assertEquals(Verdict.FAILED, r.verdict(), r.explanation());
        assertTrue(r.explanation().contains("observed at t=10.500"), r.explanation());
        // the verdict waits until nothing stamped before 10.5 can arrive
        assertTrue(r.durationMicros() >= micros(12.5), r.toString());
    }

    @Test
    void aDelayBeyondTheWindowIsInconclusiveAndNamesTheDelay() throws Exception {
        // x happened at 9.5 and arrived 3 units later; the window is 1 unit, so y (at 10) was committed at 11
        TestResult r = run(crossing(10), new Delayed(9.5, 12.5, 0), 1);
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertTrue(r.explanation().contains("happened at t=9.500 but reached the tester at t=12.500, 3.000 time"
                + " units later: more than the reorder window of 1.000"), r.explanation());
    }

    @Test
    void anInputIsPlacedWhereItsAdapterAppliedIt() throws Exception {
        // y sent at 10 (the environment allows it until 12) but applied at 10.8; x happened at 10.3, before y
        // reached the system
        TestResult passed = run(crossing(12), new Delayed(10.3, 10.4, 10.8), 2);
        assertEquals(Verdict.PASSED, passed.verdict(), passed.explanation());
        // the same output after the input was applied is a failure of the system
        TestResult failed = run(crossing(12), new Delayed(10.9, 11, 10.8), 2);
        assertEquals(Verdict.FAILED, failed.verdict(), failed.explanation());
        assertTrue(failed.explanation().contains("observed at t=10.900"), failed.explanation());
    }

    @Test
    void anInputAppliedAfterTheEnvironmentsWindowIsInconclusive() throws Exception {
        // the environment sends y by t=12: applied at 13 is outside its window
        TestResult r = run(crossing(12), new Delayed(15, 15, 13), 4);
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertTrue(r.explanation().contains("input executed too late"), r.explanation());
        assertTrue(r.explanation().contains("sent at t=10.000 and applied 3.000 time units later"), r.explanation());
    }

    @Test
    void anAcknowledgementBeyondTheWindowIsInconclusiveAndNamesTheDelay() throws Exception {
        // applied 3 units after it was sent, with a window of 2: the tester had committed to the input at 12
        TestResult r = run(crossing(20), new Delayed(15, 15, 13), 2);
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertTrue(r.explanation().startsWith("input y(), sent at t=10.000, was applied at t=13.000, 3.000 time"
                + " units later: more than the reorder window of 2.000 time units"), r.explanation());
    }

    @Test
    void anOutputTheEnvironmentCouldNotWaitForBecauseTheInputWasLateIsInconclusive() throws Exception {
        // the environment must send y at exactly 10; applied at 10.8, after x at 10.3: the model cannot let time
        // pass to 10.3 before y, so the late input, not the system, is at fault
        TestResult r = run(crossing(10), new Delayed(10.3, 10.4, 10.8), 2);
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertTrue(r.explanation().contains("was applied at t=10.800, after output x() happened at t=10.300"),
                r.explanation());
        assertTrue(r.explanation().contains("input executed too late"), r.explanation());
    }

    @Test
    void aDeadlineIsMissedOnlyWhenTheWindowHasPassed() throws Exception {
        // x happened at 4.9, in time, and arrived at 5.4: judged in time with a window of 1 unit
        TestResult inTime = run(DEADLINE, new Delayed(4.9, 5.4, 0), 1);
        assertEquals(Verdict.PASSED, inTime.verdict(), inTime.explanation());
        TestResult noWindow = run(DEADLINE, new Delayed(4.9, 5.4, 0), 0);
        assertEquals(Verdict.FAILED, noWindow.verdict(), noWindow.explanation());
        assertTrue(noWindow.explanation().startsWith("no output came by t=5.000"), noWindow.explanation());
        TestResult late = run(DEADLINE, new Delayed(5.2, 5.4, 0), 1);
        assertEquals(Verdict.FAILED, late.verdict(), late.explanation());
    }

    @Test
    void aMissedDeadlineSaysHowLongTheTesterWaitedForMessagesInTransit() throws Exception {
        TestResult r = run(DEADLINE, new Delayed(30, 30, 0), 1);
        assertEquals(Verdict.FAILED, r.verdict(), r.explanation());
        assertTrue(r.explanation().startsWith("no output came by t=5.000: the model required the system under test"
                + " to act by then (the tester waited 1.000 time units more for messages in transit)"),
                r.explanation());
    }

    @Test
    void aMissedDeadlineIsInconclusiveWhenTheAdapterKnowsTheSystemCouldNotAct() throws Exception {
        Adapter gone = new Delayed(30, 30, 0);
        TestResult r = run(DEADLINE, new Adapter() {
            @Override
            public void start(AdapterContext context) {
                gone.start(context);
            }

            @Override
            public void perform(Event input) {
            }

            @Override
            public java.util.Optional<String> unreachable() {
                return java.util.Optional.of("member m1 did not answer");
            }
        }, 1);
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        assertEquals("no output came by t=5.000, and the system under test may not have been able to act: member m1"
                + " did not answer", r.explanation());
    }

    /** Reports x as happened at {@code happened} give or take {@code uncertainty} units, when it arrives. */
    private static Adapter uncertain(double happened, double arrives, double uncertainty) {
        return new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.clock().schedule(micros(arrives), () -> context.report(Event.of("x"), micros(happened),
                        micros(uncertainty)));
            }

            @Override
            public void perform(Event input) {
            }
        };
    }

    @Test
    void anOutputWithinItsClockErrorOfTheDeadlineIsAccepted() throws Exception {
        // stamped at 5.2, after the deadline of 5, but the clocks agree only within 0.3 units: it may have been 4.9
        TestResult within = run(DEADLINE, uncertain(5.2, 5.3, 0.3), 1);
        assertEquals(Verdict.PASSED, within.verdict(), within.explanation());
        // an error bound of 0.1 unit does not reach back to 5
        TestResult beyond = run(DEADLINE, uncertain(5.2, 5.3, 0.1), 1);
        assertEquals(Verdict.FAILED, beyond.verdict(), beyond.explanation());
        assertTrue(beyond.explanation().contains("observed at t=5.200"), beyond.explanation());
    }

    @Test
    void aWidenedWindowPlacesALaterCrossingMessage() throws Exception {
        // as in aDelayBeyondTheWindowIsInconclusiveAndNamesTheDelay, but the adapter widened the window to 4 units
        // at the start, as the bus bridge does when it sees such delays
        Adapter delayed = new Delayed(9.5, 12.5, 0);
        Adapter widening = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.widenReorderWindow(micros(4));
                context.widenReorderWindow(micros(2)); // never narrows
                delayed.start(context);
            }

            @Override
            public void perform(Event input) {
                delayed.perform(input);
            }
        };
        TestResult r = run(crossing(10), widening, 1);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertEquals(1, r.outputs(), r.toString());
    }

    @Test
    void aDeadlineWaitsForAWindowWidenedWhileTheTesterWaited() throws Exception {
        // x happened at 4.9 and arrives at 7.5; at 5.5 the adapter widens the window from 1 to 3 units
        Adapter delayed = new Delayed(4.9, 7.5, 0);
        Adapter widening = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.clock().schedule(micros(5.5), () -> context.widenReorderWindow(micros(3)));
                delayed.start(context);
            }

            @Override
            public void perform(Event input) {
            }
        };
        TestResult r = run(DEADLINE, widening, 1);
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
    }

    @Test
    void aDeadlineIsJudgedWhenTheWindowWidensPastTheRunsEnd() throws Exception {
        // x never comes; while the tester waits out the window after the deadline at 5, the adapter widens the
        // window to 30 units (at 5.5) and to 40 (at 34), so that the wait ends past the run's end at 20: the deadline
        // is still judged there, not forgotten by the end of the run
        Adapter widening = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.clock().schedule(micros(5.5), () -> context.widenReorderWindow(micros(30)));
                context.clock().schedule(micros(34), () -> context.widenReorderWindow(micros(40)));
            }

            @Override
            public void perform(Event input) {
            }
        };
        TestResult r = run(DEADLINE, widening, 1);
        assertEquals(Verdict.FAILED, r.verdict(), r.explanation());
        assertTrue(r.explanation().contains("no output came by t=5"), r.explanation());
    }

    /** The environment must answer output x with input y 2 to 3 units after it. */
    private static final String ANSWER = """
            chan o_x, i_y;
            process Sut() {
                state Waiting, Asked;
                init Waiting;
                trans Waiting -> Asked { sync o_x!; },
                      Asked -> Waiting { sync i_y?; };
            }
            process Env() {
                clock e;
                state Idle, Answering { e <= 3 };
                init Idle;
                trans Idle -> Answering { sync o_x?; assign e = 0; },
                      Answering -> Idle { guard e >= 2; sync i_y!; };
            }
            system Sut, Env;
            """;

    @Test
    void anInputWindowThatClosedBeforeItsCauseArrivedIsInconclusiveNotFailed() throws Exception {
        // x happened at 5 but reached the tester at 9: the window for y, 7 to 8, had closed
        TestResult late = run(ANSWER, new Delayed(5, 9, 0), 5);
        assertEquals(Verdict.INCONCLUSIVE, late.verdict(), late.explanation());
        assertTrue(late.explanation().startsWith("no input was applied by t=8.000, when the environment's window"
                + " closed"), late.explanation());
        // arriving at 6, the tester answers in time
        TestResult inTime = run(ANSWER, new Delayed(5, 6, 0), 5);
        assertEquals(Verdict.PASSED, inTime.verdict(), inTime.explanation());
        assertEquals(1, inTime.inputs(), inTime.toString());
    }

    /** {@link Delayed}, telling the engine that it acknowledges inputs. */
    private static Adapter acknowledging(Delayed delayed) {
        return new Adapter() {
            @Override
            public void start(AdapterContext context) {
                delayed.start(context);
            }

            @Override
            public void perform(Event input) {
                delayed.perform(input);
            }

            @Override
            public boolean acknowledgesInputs() {
                return true;
            }
        };
    }

    @Test
    void aVerdictThatDependsOnAnInputsUnacknowledgedPlaceWaitsForItsAcknowledgement() throws Exception {
        // y sent at 10, x happened at 10.3; y's acknowledgement says 10.8 but arrives only at 14, after the window
        // of 2 units past x: an adapter that acknowledges inputs is waited for, and x came before y
        TestResult waited = run(crossing(20), acknowledging(new LateAck(10.3, 10.4, 10.8, 14)), 2);
        assertEquals(Verdict.PASSED, waited.verdict(), waited.explanation());
        // an adapter that does not say it acknowledges: judged with y where it was sent
        TestResult unknown = run(crossing(20), new LateAck(10.3, 10.4, 10.8, 14), 2);
        assertEquals(Verdict.FAILED, unknown.verdict(), unknown.explanation());
        // an acknowledgement that never comes: INCONCLUSIVE, naming the input
        TestResult never = run(crossing(20), acknowledging(new LateAck(10.3, 10.4, 10.8, 100)), 2);
        assertEquals(Verdict.INCONCLUSIVE, never.verdict(), never.explanation());
        assertTrue(never.explanation().startsWith("input y() was sent at t=10.000, but the acknowledgement of when it"
                + " was applied had not come by "), never.explanation());
    }

    /** Like {@link Delayed}, but the acknowledgement (applied at {@code appliedAt}) arrives at {@code ackArrives}. */
    private static final class LateAck extends Delayed {
        private final double appliedAt;
        private final double ackArrives;
        private AdapterContext context;

        LateAck(double happened, double arrives, double appliedAt, double ackArrives) {
            super(happened, arrives, 0);
            this.appliedAt = appliedAt;
            this.ackArrives = ackArrives;
        }

        @Override
        public void start(AdapterContext context) {
            this.context = context;
            super.start(context);
        }

        @Override
        public void perform(Event input) {
            long now = context.clock().nowMicros();
            context.clock().schedule(micros(ackArrives) - now, () -> context.inputApplied(1, micros(appliedAt)));
        }
    }

    /**
     * Acknowledges input y as applied at {@code appliedAt} give or take {@code error} units (its clock's error bound),
     * and reports output x as happened at {@code xAt}.
     */
    private static final class AppliedWithinError implements Adapter {
        private final double appliedAt;
        private final double error;
        private final double xAt;
        private AdapterContext context;

        AppliedWithinError(double appliedAt, double error, double xAt) {
            this.appliedAt = appliedAt;
            this.error = error;
            this.xAt = xAt;
        }

        @Override
        public void start(AdapterContext context) {
            this.context = context;
        }

        @Override
        public void perform(Event input) {
            long now = context.clock().nowMicros();
            context.clock().schedule(micros(appliedAt) - now, () -> context.inputApplied(1, micros(appliedAt),
                    micros(error)));
            context.clock().schedule(micros(xAt) - now, () -> context.report(Event.of("x"), micros(xAt)));
        }

        @Override
        public boolean acknowledgesInputs() {
            return true;
        }
    }

    @Test
    void anOutputAfterAnInputTheEnvironmentAllowedOnlyWithinItsClockErrorIsInconclusiveNotFailed() throws Exception {
        // y must come at 10; its acknowledgement says 10.8 give or take 1: in time only within the error. x at 11.5
        // is not allowed after y, but y may have come after its window closed: the test left the environment's
        // assumptions, and the system is not to blame
        TestResult doubtful = run(crossing(10), new AppliedWithinError(10.8, 1, 11.5), 2);
        assertEquals(Verdict.INCONCLUSIVE, doubtful.verdict(), doubtful.explanation());
        assertTrue(doubtful.explanation().startsWith("output x() observed at t=11.500 is not what the model allows"
                + " after input y(), which was applied at t=10.800 give or take 1.000 time units: the environment"
                + " allowed it only within that clock error, so it may have come after its window closed (input"
                + " executed too late)"), doubtful.explanation());
        // applied at 10 give or take 1, where the environment allows it: x after it fails the system
        TestResult inTime = run(crossing(10), new AppliedWithinError(10, 1, 11.5), 2);
        assertEquals(Verdict.FAILED, inTime.verdict(), inTime.explanation());
    }

    @Test
    void anInputIsNotCommittedWhileItsAcknowledgementIsExpected() throws Exception {
        // applied 3 units after it was sent (window 2): an adapter that acknowledges inputs is waited for, and the
        // input placed where it was applied, after x at 12.5
        TestResult placed = run(crossing(20), acknowledging(new LateAck(12.5, 12.6, 13, 13.1)), 2);
        assertEquals(Verdict.PASSED, placed.verdict(), placed.explanation());
    }
}
