package io.dtron.api;

import io.dtron.api.internal.TestHooks;
import io.dtron.api.internal.TesterSide;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.bus.internal.EpochClock;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.Waits;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * The run clock counts the run's time on the tester's clock: tasks fire at the tester's run times even when
 * RUN_START reaches a member late or the member's clock is off. The tester's clock here is the test's unshifted
 * wall clock, so {@code EpochClock.nowNanos() - timeZero} is the tester's run time.
 */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class RunClockTest {
    private static final long MS = 1_000_000;
    private static final IDtronChannel SLOW = IDtronChannel.of("slow", "millis");
    private static final IDtronChannel RESET = IDtronChannel.of("reset");
    private final String cluster = TestClusters.uniqueName("runClock");

    /** Listens to {@code slow(millis)} by sleeping that long, which holds up the messages after it. */
    private static void addSlowListener(Dtron member) {
        member.addDtronListener(new DtronListener(SLOW) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                try {
                    Thread.sleep(message.getVariables().get("millis"));
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            }
        });
    }

    /** Starts a run and returns its time 0 on the tester's clock. */
    private static long startRun(Dtron tester, Inbox starts, int unitMicros) throws InterruptedException {
        tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", unitMicros)));
        return starts.take().getEventTimeNanos();
    }

    /**
     * Schedules, from the member's RUN_START listener, one task at {@code units} and a mark 1 ms after it; both
     * record the tester's time (the test's clock) in {@code fired}, the task first.
     */
    private static BlockingQueue<Long> fireAtFromRunStart(Dtron member, double units,
            AtomicReference<Double> startSeenAtUnits) {
        BlockingQueue<Long> fired = new LinkedBlockingQueue<>();
        member.addDtronListener(new DtronListener(Dtron.RUN_START) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                RunClock clock = getDtron().runClock();
                assertTrue(clock.isRunning());
                startSeenAtUnits.set(clock.nowUnits());
                clock.scheduleAt(units, () -> fired.add(EpochClock.nowNanos()));
                clock.scheduleAt(units + justAfter(clock), () -> fired.add(EpochClock.nowNanos()));
            }
        });
        return fired;
    }

    /** 1 ms in the clock's time units. */
    private static double justAfter(RunClock clock) {
        return MS / (clock.timeUnitMicros() * 1_000.0);
    }

    /**
     * Asserts that a task due at {@code dueNanos} fired then: not early beyond the estimate's error, and before the
     * mark due 1 ms after it ran. The clock runs its tasks on one thread in the order of their due times, so
     * however late a loaded machine wakes that thread, the mark cannot run first unless the task was late by more
     * than 1 ms on the clock's own time.
     */
    private static void assertFiredAt(long dueNanos, long firedNanos, long markNanos, long errorNanos,
            String context) {
        String what = context + "fired at " + firedNanos / 1e6 + " ms of the run, due at " + dueNanos / 1e6 + " ms (error "
                + errorNanos / 1e6 + " ms), the mark 1 ms after it ran at " + markNanos / 1e6 + " ms";
        // not early beyond the estimate's error (and a little, as the estimate may have changed since it fired)
        assertTrue(firedNanos >= dueNanos - errorNanos - 10 * MS, what);
        assertTrue(firedNanos <= markNanos, what);
    }

    /** Takes a task's time and its mark's from {@code fired} and asserts them with {@link #assertFiredAt}. */
    private static void assertFiredAt(long dueNanos, BlockingQueue<Long> fired, long timeZero, long errorNanos,
            String context) throws InterruptedException {
        Long at = fired.poll(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS);
        Long mark = fired.poll(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS);
        assertNotNull(at, context + "the task did not fire");
        assertNotNull(mark, context + "the mark did not run");
        assertFiredAt(dueNanos, at - timeZero, mark - timeZero, errorNanos, context);
    }

    @Test
    void aTaskFiresAtTheTestersRunTimeThoughRunStartArrivedLateAtAShiftedMember() throws Exception {
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
                Dtron ahead = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("ahead"),
                        Duration.ofMillis(50)).build());
                Dtron behind = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("behind"),
                        Duration.ofMillis(-50)).build())) {
            Inbox starts = new Inbox(Dtron.RUN_START);
            tester.addDtronListener(starts);
            ClockOffsetTest.awaitOffset(ahead);
            ClockOffsetTest.awaitOffset(behind);
            addSlowListener(ahead);
            addSlowListener(behind);
            AtomicReference<Double> aheadSawStart = new AtomicReference<>();
            AtomicReference<Double> behindSawStart = new AtomicReference<>();
            BlockingQueue<Long> aheadFired = fireAtFromRunStart(ahead, 10, aheadSawStart);
            BlockingQueue<Long> behindFired = fireAtFromRunStart(behind, 10, behindSawStart);

            // RUN_START reaches the listeners 800 ms after the slow message: 8 units late, less what the test
            // thread took to send it; a task due 10 units after the listener was called would fire at 1800 ms
            long slowSent = EpochClock.nowNanos();
            tester.send(SLOW.constructValued(Map.of("millis", 800)));
            long timeZero = startRun(tester, starts, 100_000); // 10 units = 1000 ms
            assertFiredAt(1000 * MS, aheadFired, timeZero, ahead.getClockErrorNanos(), "ahead: ");
            assertFiredAt(1000 * MS, behindFired, timeZero, behind.getClockErrorNanos(), "behind: ");
            String seen = "RUN_START reached the listeners at " + aheadSawStart.get() + " and " + behindSawStart.get()
                    + " units; ";
            // the listeners got RUN_START after slow's listener returned, 800 ms or more after slow was sent: late by
            // that much less the time (load decides how long) the test thread took to start the run
            double lateUnits = (slowSent + 800 * MS - timeZero) / (100.0 * MS);
            double errorUnits = Math.max(ahead.getClockErrorNanos(), behind.getClockErrorNanos()) / (100.0 * MS);
            assertTrue(aheadSawStart.get() >= lateUnits - errorUnits - 0.1
                    && behindSawStart.get() >= lateUnits - errorUnits - 0.1, seen + "late by " + lateUnits);
        }
    }

    @Test
    void theClockFollowsAnEstimateThatComesAfterRunStartAndNeverGoesBack() throws Exception {
        // no tester option: the member learns the tester from RUN_START, while its clock is 50 ms ahead
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").build());
                Dtron ahead = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("ahead"),
                        Duration.ofMillis(50)).build())) {
            assertTrue(tester.awaitMembers(2, Duration.ofSeconds(10)));
            Inbox starts = new Inbox(Dtron.RUN_START);
            tester.addDtronListener(starts);
            AtomicReference<Double> sawStart = new AtomicReference<>();
            BlockingQueue<Long> fired = fireAtFromRunStart(ahead, 10, sawStart);
            assertFalse(ahead.hasClockOffset());

            long timeZero = startRun(tester, starts, 50_000);
            long previous = Long.MIN_VALUE;
            long until = System.nanoTime() + 300 * MS;
            while (System.nanoTime() < until) {
                if (ahead.runClock().isRunning()) {
                    long now = ahead.runClock().nowNanos();
                    assertTrue(now >= previous, now + " after " + previous);
                    previous = now;
                }
            }
            ClockOffsetTest.awaitOffset(ahead); // it pings the tester it learned from RUN_START
            assertEquals(java.util.Optional.of("tester"), ahead.getTester());
            assertTrue(tester.hasClockOffset(), "the member that sent RUN_START is the tester");
            assertFiredAt(500 * MS, fired, timeZero, ahead.getClockErrorNanos(), "");
        }
    }

    @Test
    void fixedRateTasksFireAtMultiplesOfThePeriodUntilTheRunStops() throws Exception {
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
                Dtron member = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("member"),
                        Duration.ofMillis(-30)).build())) {
            Inbox starts = new Inbox(Dtron.RUN_START);
            Inbox stops = new Inbox(Dtron.RUN_STOP);
            tester.addDtronListener(starts);
            member.addDtronListener(stops);
            ClockOffsetTest.awaitOffset(member);
            BlockingQueue<Long> ticks = new LinkedBlockingQueue<>();
            BlockingQueue<Long> marks = new LinkedBlockingQueue<>();
            AtomicReference<RunClock.Task> task = new AtomicReference<>();
            member.addDtronListener(new DtronListener(Dtron.RUN_START) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    RunClock clock = getDtron().runClock();
                    task.set(clock.scheduleAtFixedRate(2, 2, () -> ticks.add(EpochClock.nowNanos())));
                    clock.scheduleAtFixedRate(2 + justAfter(clock), 2, () -> marks.add(EpochClock.nowNanos()));
                }
            });
            long timeZero = startRun(tester, starts, 40_000); // every 80 ms from 80 ms
            RunClock clock = member.runClock();
            List<Long> times = new ArrayList<>();
            for (int k = 1; k <= 5; k++) {
                Long at = ticks.poll(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS);
                Long mark = marks.poll(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS);
                assertNotNull(at, "tick " + k);
                assertNotNull(mark, "mark " + k);
                times.add(at - timeZero);
                assertFiredAt(k * 80 * MS, at - timeZero, mark - timeZero, member.getClockErrorNanos(), "tick " + k
                        + ": ");
            }
            assertEquals(40_000, clock.timeUnitMicros());
            assertTrue(clock.nowUnits() >= 10 - 0.2, clock.nowUnits() + " units after " + times);

            tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
            stops.take();
            assertFalse(clock.isRunning());
            assertTrue(task.get().isCancelled(), "the run's tasks are cancelled when it stops");
            ticks.clear();
            // a tick under way when the run stopped finishes (however long load holds up its thread); none starts
            if (ticks.poll(300, TimeUnit.MILLISECONDS) != null) {
                assertNull(ticks.poll(300, TimeUnit.MILLISECONDS), "no tick after the run stopped");
            }
            assertTrue(clock.scheduleAt(1, () -> ticks.add(0L)).isCancelled(), "no run, nothing scheduled");
        }
    }

    @Test
    void withoutARunNothingIsScheduledAndTheClockHasNoTime() {
        try (Dtron member = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            RunClock clock = member.runClock();
            assertFalse(clock.isRunning());
            assertEquals(0, clock.timeUnitMicros());
            assertEquals("", clock.runId());
            assertThrows(IllegalStateException.class, clock::nowNanos);
            RunClock.Task task = clock.scheduleAt(1, () -> { });
            assertTrue(task.isCancelled());
            assertFalse(task.cancel());
            assertTrue(clock.scheduleAtNanos(1, () -> { }).isCancelled());
            assertTrue(clock.scheduleAtFixedRate(1, 1, () -> { }).isCancelled());
        }
    }

    @Test
    void tasksCanBeCancelledAndTheRunStopsWhenItsTesterLeaves() throws Exception {
        Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
        try (Dtron member = Dtron.connect(TestClusters.inJvm(cluster).memberName("member").build())) {
            Inbox starts = new Inbox(Dtron.RUN_START);
            member.addDtronListener(starts);
            Inbox resets = new Inbox(RESET);
            member.addDtronListener(resets);
            TesterSide.of(tester).setRunId("run-1");
            tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 1_000)));
            long timeZero = starts.take().getEventTimeNanos();
            RunClock clock = member.runClock();
            assertTrue(clock.isRunning());
            assertEquals("run-1", clock.runId());
            assertThrows(IllegalArgumentException.class, () -> clock.scheduleAtFixedRate(0, 0, () -> { }));
            assertThrows(IllegalArgumentException.class, () -> clock.scheduleAt(Double.NaN, () -> { }));

            BlockingQueue<String> ran = new LinkedBlockingQueue<>();
            RunClock.Task cancelled = clock.scheduleAt(300, () -> ran.add("cancelled"));
            RunClock.Task later = clock.scheduleAt(100_000, () -> ran.add("later"));
            clock.scheduleAt(200, () -> ran.add("kept"));
            assertTrue(cancelled.cancel());
            assertFalse(cancelled.cancel());
            assertEquals("kept", ran.poll(10, TimeUnit.SECONDS));
            assertNull(ran.poll(300, TimeUnit.MILLISECONDS));

            // a message's run time: its event time on the tester's clock since time 0
            tester.send(RESET.constructValued(Map.of()));
            IDtronChannelValued reset = resets.take();
            assertEquals(reset.getEventTimeNanos() - timeZero, clock.runNanosOf(reset));
            assertTrue(clock.runNanosOf(reset) <= clock.nowNanos());

            tester.close();
            Waits.await("the run clock stopped with its tester gone").until(() -> !clock.isRunning());
            assertTrue(later.isCancelled());
        } finally {
            tester.close();
        }
    }
}
