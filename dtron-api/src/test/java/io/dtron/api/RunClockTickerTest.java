package io.dtron.api;

import io.dtron.api.internal.TestHooks;
import io.dtron.api.internal.TesterSide;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testadapter.RunClockTicker;
import io.dtron.testadapter.RunClockTickerMain;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.Waits;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicReference;
import java.util.function.LongConsumer;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * A ticker on the run clock, its clock ahead of the tester's (80 ms in this JVM, 120 ms in its own), ticks at the
 * tester's run times: each tick happened (event time plus the offset it carries) at a multiple of the period from
 * time 0 or from the last reset.
 *
 * <p>What load cannot change: the run clock never runs a task before it is due (on its estimate of the tester's
 * clock), and it runs its tasks on one thread in the order of their due times. So a tick is never early beyond the
 * estimate's error, and in the same JVM a task the test schedules just after a tick's due time runs after that tick
 * was sent, however late the machine wakes the clock's thread: a tick one period late would be sent after it.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class RunClockTickerTest {
    private static final long MS = 1_000_000;
    private static final IDtronChannel TICK = IDtronChannel.of("tick", "seq");
    private static final IDtronChannel RESET = IDtronChannel.of("reset");
    private static final int UNIT_MICROS = 20_000;
    private static final long PERIOD = 10 * UNIT_MICROS * 1_000L; // 10 units of 20 ms
    /** How much later than the tick's due time the test's own task runs: far less than a period. */
    private static final long AFTER_DUE = MS;

    /** Asserts the tick's number, and that it happened no earlier than due, give or take its offset's error. */
    private static String assertTickNotEarly(long due, IDtronChannelValued tick, long timeZero, int seq) {
        long happened = tick.getEventTimeNanos() + tick.getClockOffsetNanos() - timeZero;
        long arrived = tick.getReceiveTimeNanos() - timeZero;
        String what = "tick " + tick.getVariables() + " happened at " + happened / 1e6 + " ms, arrived at "
                + arrived / 1e6 + " ms, due at " + due / 1e6 + " ms (error " + tick.getClockErrorNanos() / 1e6 + ")";
        assertEquals(seq, tick.getVariables().get("seq"), what);
        assertTrue(tick.getClockErrorNanos() > 0, "the tick carries an estimate of the ticker's offset: " + what);
        // never early: the clock runs a task no sooner than due by its estimate (10 ms: the estimate may have
        // improved since the tick was scheduled)
        assertTrue(happened >= due - tick.getClockErrorNanos() - 10 * MS, what);
        // and it arrived after it happened (both on the tester's clock, within the estimate's error)
        assertTrue(arrived >= happened - tick.getClockErrorNanos(), what);
        return what;
    }

    /** When the test's task after a tick's due time ran, on the ticker's own clock; restarts count from 1. */
    private record Mark(int restart, long ranAt) {
    }

    /**
     * Schedules on the ticker's run clock, from the same messages that (re)start the ticker, a task just after
     * each tick's due time; the queue gets when it ran.
     */
    private static BlockingQueue<Mark> markAfterEachDueTime(Dtron adapter) {
        BlockingQueue<Mark> marks = new LinkedBlockingQueue<>();
        AtomicReference<RunClock.Task> marking = new AtomicReference<>();
        AtomicInteger restarts = new AtomicInteger();
        LongConsumer restart = fromNanos -> {
            RunClock.Task old = marking.getAndSet(null);
            if (old != null) {
                old.cancel();
            }
            int restartNo = restarts.incrementAndGet();
            RunClock clock = adapter.runClock();
            double unitNanos = clock.timeUnitMicros() * 1_000.0;
            marking.set(clock.scheduleAtFixedRate((fromNanos + PERIOD + AFTER_DUE) / unitNanos, PERIOD / unitNanos,
                    () -> marks.add(new Mark(restartNo, adapter.currentTimeNanos()))));
        };
        // added after the ticker's listeners, so that they run after them (one dispatcher, in the order added)
        adapter.addDtronListener(new DtronListener(Dtron.RUN_START) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                restart.accept(0);
            }
        });
        adapter.addDtronListener(new DtronListener(RESET) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                if (adapter.runClock().isRunning()) {
                    restart.accept(adapter.runClock().runNanosOf(message));
                }
            }
        });
        return marks;
    }

    /**
     * Asserts that the tick was sent (on the ticker's own clock) before the test's task just after its due time ran:
     * the next mark of the same restart.
     */
    private static void assertTickBefore(IDtronChannelValued tick, BlockingQueue<Mark> marks, int restart,
            String what) throws InterruptedException {
        Mark mark;
        do {
            mark = marks.poll(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS);
            assertNotNull(mark, "the test's task did not run: " + what);
        } while (mark.restart() < restart); // the tasks of the period before a reset
        assertEquals(restart, mark.restart(), what);
        assertTrue(tick.getEventTimeNanos() <= mark.ranAt(), "not sent before the task " + AFTER_DUE / 1e6
                + " ms after its due time ran (" + (tick.getEventTimeNanos() - mark.ranAt()) / 1e6 + " ms later): "
                + what);
    }

    @Test
    void ticksAtTheTestersRunTimesAndRestartsAtTheResetsRunTime() throws Exception {
        String cluster = TestClusters.uniqueName("runClockTicker");
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
                Dtron adapter = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("ticker"),
                        Duration.ofMillis(80)).build());
                RunClockTicker ticker = new RunClockTicker()) {
            ticker.start(adapter);
            BlockingQueue<Mark> marks = markAfterEachDueTime(adapter);
            ClockOffsetTest.awaitOffset(adapter);
            Inbox ticks = new Inbox(TICK);
            Inbox starts = new Inbox(Dtron.RUN_START);
            Inbox resets = new Inbox(RESET);
            tester.addDtronListener(ticks);
            tester.addDtronListener(starts);
            tester.addDtronListener(resets);

            tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", UNIT_MICROS)));
            long timeZero = starts.take().getEventTimeNanos();
            for (int k = 1; k <= 3; k++) {
                IDtronChannelValued tick = ticks.take();
                assertTickBefore(tick, marks, 1, assertTickNotEarly(k * PERIOD, tick, timeZero, k));
            }
            // the reset falls somewhere in the fourth period, wherever the machine's load puts it
            tester.send(RESET.constructValued(Map.of()));
            long resetAt = resets.take().getEventTimeNanos() - timeZero;
            // ticks due before the reset reached the ticker may still come; the first of the new period is seq 1
            IDtronChannelValued tick = ticks.take();
            while (tick.getVariables().get("seq") != 1) {
                tick = ticks.take();
            }
            for (int k = 1; k <= 2; k++) {
                if (k > 1) {
                    tick = ticks.take();
                }
                assertTickBefore(tick, marks, 2, assertTickNotEarly(resetAt + k * PERIOD, tick, timeZero, k));
            }
            tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
            Waits.await("the ticker's run clock stopped").until(() -> !adapter.runClock().isRunning());
            // the ticker's answer to a probe comes after every tick it sent: then all of them have arrived
            assertEquals(java.util.Set.of(adapter.getMemberId()),
                    TesterSide.of(tester).probe(List.of(adapter.getMemberId()), Waits.TIMEOUT));
            while (ticks.poll(0) != null) {
                // a tick sent before the stop
            }
            // a tick under way when the run stopped finishes (however long load holds up its thread); none starts
            if (ticks.poll(PERIOD / MS + 100) != null) {
                assertNull(ticks.poll(PERIOD / MS + 100), "no tick after the run stopped");
            }
        }
    }

    @Test
    void aTickerInItsOwnJvmWithItsClock120MsAheadNeverTicksEarlyAndCarriesItsOffset(@TempDir Path dir) throws Exception {
        String cluster = TestClusters.uniqueName("runClockTickerJvm");
        int port = FreePorts.range(FreePorts.BUS_RANGE);
        Dtron tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("tester").tester(true)
                .port(port).portRange(FreePorts.BUS_RANGE).build());
        try (ChildJvm child = ChildJvm.start(RunClockTickerMain.class, dir.resolve("ticker.log"), cluster, "ticker",
                "correct", "120", "1", Integer.toString(port))) {
            child.awaitOutput("offset", Waits.TIMEOUT);
            Inbox ticks = new Inbox(TICK);
            Inbox starts = new Inbox(Dtron.RUN_START);
            tester.addDtronListener(ticks);
            tester.addDtronListener(starts);
            tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", UNIT_MICROS)));
            long timeZero = starts.take().getEventTimeNanos();
            long previous = Long.MIN_VALUE;
            for (int k = 1; k <= 3; k++) {
                IDtronChannelValued tick = ticks.take();
                String what = assertTickNotEarly(k * PERIOD, tick, timeZero, k);
                // the ticks keep their order (the bus keeps a sender's order). No thread of this JVM can mark the
                // due times, so lateness is judged by the test above; with the clock ahead, an offset ignored or
                // applied the wrong way makes every tick 120 or 240 ms early, which the bound above rejects
                long happened = tick.getEventTimeNanos() + tick.getClockOffsetNanos() - timeZero;
                assertTrue(happened > previous, what);
                previous = happened;
                assertTrue(Math.abs(tick.getClockOffsetNanos() + 120 * MS) <= tick.getClockErrorNanos(),
                        tick.getClockOffsetNanos() + " +/- " + tick.getClockErrorNanos());
            }
            tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
            tester.close();
            assertEquals(0, child.waitFor(Waits.TIMEOUT), child.output());
        } finally {
            tester.close();
        }
    }
}
