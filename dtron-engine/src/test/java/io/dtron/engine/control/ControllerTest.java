package io.dtron.engine.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestOptions;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.engine.sim.Mutant;
import io.dtron.engine.sim.Mutants;
import io.dtron.engine.verify.Query;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The controller on a small closed model, in virtual time: a controller that may command a or b, each answered by
 * done 2 to 3 units later; the goal policy steers toward the goal, a reading too early raises the alarm at once, a
 * reading on its way when its deadline passes is judged at its own time (no false alarm), a lost plant stops the run,
 * and a version the controller cannot run (its safe location gone) is refused when it would be taken, the run going
 * on.
 */
class ControllerTest {
    private static final String MODEL = """
            chan i_a, i_b, i_stop, o_done;
            process Ctl() {
                clock c;
                state Start { c <= 1 }, WaitA, WaitB, GotB { c <= 1 }, Safe;
                init Start;
                trans
                    Start -> WaitA { sync i_a!; assign c = 0; },
                    Start -> WaitB { sync i_b!; assign c = 0; },
                    WaitA -> Start { sync o_done?; assign c = 0; },
                    WaitB -> GotB { sync o_done?; assign c = 0; },
                    GotB -> WaitA { sync i_a!; assign c = 0; },
                    WaitA -> Safe { guard c > 3; sync i_stop!; };
            }
            process Dev() {
                clock d;
                state Idle, Busy { d <= 3 };
                init Idle;
                trans
                    Idle -> Busy { sync i_a?; assign d = 0; },
                    Idle -> Busy { sync i_b?; assign d = 0; },
                    Busy -> Idle { guard d >= 2; sync o_done!; },
                    Idle -> Idle { sync i_stop?; },
                    Busy -> Idle { sync i_stop?; };
            }
            system Ctl, Dev;
            """;

    private static Network model() throws Exception {
        return ModelLoader.load("ab.xta", MODEL);
    }

    private static TestOptions options(long seed) {
        return TestOptions.defaults(seed).withTimeout(50);
    }

    /** The commands a run sent, in order. */
    private static List<String> commands(Controller controller) {
        List<String> sent = new ArrayList<>();
        controller.addListener(new ControlListener() {
            @Override
            public void commandSent(Event command, long micros) {
                sent.add(command.channel());
            }
        });
        return sent;
    }

    @Test
    void theGoalPolicySteersTowardTheGoalWhereEagerChoosesAtRandom() throws Exception {
        Network n = model();
        TestInterface names = TestInterface.fromNames(n);
        List<String> eagerFirst = new ArrayList<>();
        for (long seed = 1; seed <= 10; seed++) {
            Controller goal = new Controller(n, names, new ModelSystem(n, names, seed), options(seed))
                    .policy(ControlPolicy.GOAL, List.of("E<> Ctl.GotB"));
            List<String> sent = commands(goal);
            assertEquals(ControlResult.Outcome.COMPLETED, goal.run().outcome());
            assertEquals("b", sent.get(0), "seed " + seed + ": b leads to the goal");
            // the controller's own seeds spread out: the first choices of java.util.Random's nearby seeds agree
            Controller eager = new Controller(n, names, new ModelSystem(n, names, seed),
                    options(ModelSystem.seedFor(seed)));
            List<String> sentEager = commands(eager);
            assertEquals(ControlResult.Outcome.COMPLETED, eager.run().outcome());
            eagerFirst.add(sentEager.get(0));
        }
        assertTrue(eagerFirst.contains("a") && eagerFirst.contains("b"), "eager chooses at random: " + eagerFirst);
        assertThrows(IllegalArgumentException.class, () -> new Controller(n, names, new ModelSystem(n, names, 1),
                options(1)).policy(ControlPolicy.GOAL, List.of()));
    }

    @Test
    void aReadingTooEarlyRaisesTheAlarmWhenItComes() throws Exception {
        Network n = model();
        TestInterface names = TestInterface.fromNames(n);
        Mutant early = Mutants.derive(n, names, Duration.ofSeconds(10)).stream()
                .filter(m -> m.kind() == Mutant.Kind.OUTPUT_EARLY).findFirst().orElseThrow();
        boolean alarmed = false;
        for (long seed = 1; seed <= 20 && !alarmed; seed++) {
            List<Long> readings = new ArrayList<>();
            Controller controller = new Controller(n, names, new ModelSystem(early.network(), names, seed),
                    options(seed)).safeAction(SafeAction.location("Ctl.Safe"));
            controller.addListener(new ControlListener() {
                @Override
                public void readingTaken(Event reading, long micros) {
                    readings.add(micros);
                }
            });
            ControlResult r = controller.run();
            if (r.outcome() == ControlResult.Outcome.ALARM) {
                alarmed = true;
                String at = ControlResult.time(r.alarmMicros(), 1000);
                assertTrue(r.reason().startsWith("reading done() at " + at + " is not allowed then (too early). The"
                        + " model allowed these readings: done between t="), r.reason());
                assertTrue(readings.stream().allMatch(t -> t < r.alarmMicros()), "raised when the reading came");
                assertEquals("stop()", r.safeAction());
            } else {
                assertEquals(ControlResult.Outcome.COMPLETED, r.outcome(), r.toString());
            }
        }
        assertTrue(alarmed, "a plant that may answer a unit early is caught within 20 seeds");
    }

    /**
     * A plant whose readings are on their way when the deadline passes (a plant on the bus: the controller's question
     * whether it is there flushes them): each done comes, at {@code units} after its command, only when asked.
     */
    private static Adapter inTransit(double units) {
        return new Adapter() {
            private AdapterContext context;
            private long sentAt = -1;

            @Override
            public void start(AdapterContext runContext) {
                context = runContext;
            }

            @Override
            public void perform(Event input) {
                sentAt = input.channel().equals("stop") ? -1 : context.clock().nowMicros();
            }

            @Override
            public java.util.Optional<String> unreachable() {
                if (sentAt >= 0) {
                    context.report(new Event("done", java.util.Map.of()), sentAt + Math.round(units * 1000));
                    sentAt = -1;
                }
                return java.util.Optional.empty();
            }
        };
    }

    @Test
    void commandsKeepTheirBoundByTheStampsWhenReadingsComeBetweenTicks() throws Exception {
        // go when the controller's clock reaches 5 units, which only go resets; the plant reads a three times after
        // each go, between the ticks of a millisecond: the readings must not move the controller's clock
        Network n = ModelLoader.load("go.xta", """
                chan i_go, o_a;
                process Ctl() { clock e; state E; init E;
                    trans E -> E { guard e >= 5; sync i_go!; assign e = 0; }, E -> E { sync o_a?; }; }
                process Plant() { state S; init S; trans S -> S { sync i_go?; }, S -> S { sync o_a!; }; }
                system Ctl, Plant;
                """);
        TestInterface names = TestInterface.fromNames(n);
        long unit = 1_000_000;
        Adapter plant = new Adapter() {
            private AdapterContext context;

            @Override
            public void start(AdapterContext started) {
                context = started;
            }

            @Override
            public void perform(Event input) {
                long now = context.clock().nowMicros();
                for (double after : new double[] {0.3337, 1.4441, 3.7773}) {
                    long delay = Math.round(after * unit);
                    context.clock().schedule(delay, () -> context.report(Event.of("a"), now + delay));
                }
            }
        };
        Controller controller = new Controller(n, names, plant, TestOptions.defaults(7).withTimeUnit(unit)
                .withTimeout(400));
        List<Long> sent = new ArrayList<>();
        controller.addListener(new ControlListener() {
            @Override
            public void commandSent(Event command, long micros) {
                sent.add(micros);
            }
        });
        ControlResult r = controller.run();
        assertEquals(ControlResult.Outcome.COMPLETED, r.outcome(), r.toString());
        assertTrue(sent.size() >= 70, r.toString());
        for (int i = 1; i < sent.size(); i++) {
            assertTrue(sent.get(i) - sent.get(i - 1) >= 5 * unit, "go at " + sent.get(i) + " after " + sent.get(i - 1));
        }
    }

    @Test
    void aReadingOnItsWayAtTheDeadlineIsTakenAtItsTimeAndOneAfterItIsLate() throws Exception {
        Network n = model();
        TestInterface names = TestInterface.fromNames(n);
        // done 2.5 units after each command, within its window (2 to 3), comes when the deadline has passed
        ControlResult taken = new Controller(n, names, inTransit(2.5), options(1)).run();
        assertEquals(ControlResult.Outcome.COMPLETED, taken.outcome(), taken.toString());
        assertEquals(0, taken.alarms());
        assertTrue(taken.readings() > 10, taken.toString());
        // 3.5 units after its command: it happened after the deadline, and is too late
        ControlResult late = new Controller(n, names, inTransit(3.5), options(1)).run();
        assertEquals(ControlResult.Outcome.ALARM, late.outcome(), late.toString());
        assertTrue(late.reason().startsWith("reading done() at t=3.500 is too late"), late.reason());
    }

    @Test
    void aPlantLostStopsTheRunWithTheReason() throws Exception {
        Network n = model();
        TestInterface names = TestInterface.fromNames(n);
        Adapter lost = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.clock().schedule(7 * 1000, () -> context.inconclusive("the plant's connection dropped"));
            }

            @Override
            public void perform(Event input) {
            }
        };
        ControlResult r = new Controller(n, names, lost, options(1)).run();
        // the plant never answers: by the deadline of the first command (3 units) that is an alarm, before the loss
        assertEquals(ControlResult.Outcome.ALARM, r.outcome(), r.toString());
        assertNull(r.safeAction());
        Adapter lostAtOnce = new Adapter() {
            @Override
            public void start(AdapterContext context) {
                context.clock().schedule(500, () -> context.inconclusive("the plant's connection dropped"));
            }

            @Override
            public void perform(Event input) {
            }
        };
        ControlResult stopped = new Controller(n, names, lostAtOnce, options(1)).run();
        assertEquals(ControlResult.Outcome.STOPPED, stopped.outcome(), stopped.toString());
        assertEquals("the plant's connection dropped (at t=0.500)", stopped.reason());
        assertEquals(0, stopped.alarms());
    }

    @Test
    void aVersionTheControllerCannotRunIsRefusedWhenItWouldBeTaken() throws Exception {
        Network n = model();
        TestInterface names = TestInterface.fromNames(n);
        Network noSafe = ModelLoader.load("ab2.xta", MODEL.replace(", Safe;", ";")
                .replace("WaitA -> Safe { guard c > 3; sync i_stop!; };", "WaitA -> WaitA { guard c > 3; sync i_stop!; };")
                .replace("GotB -> WaitA { sync i_a!; assign c = 0; },", "GotB -> WaitA { sync i_a!; assign c = 0; },"));
        ModelVersion.Check check = ModelVersion.check(new ModelVersion("ab2.xta", noSafe,
                TestInterface.fromNames(noSafe)), names, List.of(Query.parse("E<> Ctl.GotB")));
        assertTrue(check.accepted(), check.refusal());
        Controller controller = new Controller(n, names, new ModelSystem(n, names, 3), options(3))
                .safeAction(SafeAction.location("Ctl.Safe"));
        controller.offer(check);
        ControlResult r = controller.run();
        assertEquals(ControlResult.Outcome.COMPLETED, r.outcome(), r.toString());
        assertTrue(r.versions().isEmpty());
        assertEquals(List.of("ab2.xta: it cannot be run: the safe location Ctl.Safe: Ctl has no location Safe"),
                r.refused());
    }

    @Test
    void aSafeActionMustBeACommand() throws Exception {
        Network n = model();
        TestInterface names = TestInterface.fromNames(n);
        Controller controller = new Controller(n, names, new ModelSystem(n, names, 1), options(1));
        IllegalArgumentException output = assertThrows(IllegalArgumentException.class,
                () -> controller.safeAction(SafeAction.channel("o_done")));
        assertEquals("the safe action o_done is no input (command) of the model; its inputs are [i_a, i_b, i_stop]",
                output.getMessage());
        IllegalArgumentException none = assertThrows(IllegalArgumentException.class,
                () -> controller.safeAction(SafeAction.location("Ctl.Start")));
        assertEquals("the safe location Ctl.Start must be entered by edges that send one command, the safe action; no"
                + " edge into it sends a command", none.getMessage());
    }
}
