package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testadapter.RunClockTicker;
import io.dtron.testadapter.RunClockTickerMain;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Inbox;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * A ticker on the run clock, its clock 80 ms ahead of the tester's, ticks at the tester's run times: each tick
 * happened (event time plus the offset it carries) at a multiple of the period from time 0 or from the last reset.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class RunClockTickerTest {
    private static final long MS = 1_000_000;
    private static final IDtronChannel TICK = IDtronChannel.of("tick", "seq");
    private static final IDtronChannel RESET = IDtronChannel.of("reset");
    private static final long PERIOD = 10 * 20 * MS; // 10 units of 20 ms

    private static void assertTickAt(long due, IDtronChannelValued tick, long timeZero, int seq) {
        long happened = tick.getEventTimeNanos() + tick.getClockOffsetNanos() - timeZero;
        long arrived = tick.getReceiveTimeNanos() - timeZero;
        String what = "tick " + tick.getVariables() + " happened at " + happened / 1e6 + " ms, arrived at "
                + arrived / 1e6 + " ms, due at " + due / 1e6 + " ms (error " + tick.getClockErrorNanos() / 1e6 + ")";
        assertEquals(seq, tick.getVariables().get("seq"), what);
        // late only by what a loaded machine takes to wake the clock's thread and deliver the tick
        assertTrue(Math.abs(happened - due) <= tick.getClockErrorNanos() + 300 * MS, what);
        assertTrue(arrived >= due - tick.getClockErrorNanos() - 10 * MS && arrived <= due + 400 * MS, what);
    }

    @Test
    void ticksAtTheTestersRunTimesAndRestartsAtTheResetsRunTime() throws Exception {
        String cluster = TestClusters.uniqueName("runClockTicker");
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
                Dtron adapter = Dtron.connect(TestClusters.inJvm(cluster).memberName("ticker")
                        .clockShiftForTesting(Duration.ofMillis(80)).build());
                RunClockTicker ticker = new RunClockTicker()) {
            ticker.start(adapter);
            ClockOffsetTest.awaitOffset(adapter);
            Inbox ticks = new Inbox(TICK);
            Inbox starts = new Inbox(Dtron.RUN_START);
            Inbox resets = new Inbox(RESET);
            tester.addDtronListener(ticks);
            tester.addDtronListener(starts);
            tester.addDtronListener(resets);

            tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 20_000)));
            long timeZero = starts.take().getEventTimeNanos();
            for (int k = 1; k <= 3; k++) {
                assertTickAt(k * PERIOD, ticks.take(), timeZero, k);
            }
            Thread.sleep(PERIOD / MS / 2);
            tester.send(RESET.constructValued(Map.of()));
            long resetAt = resets.take().getEventTimeNanos() - timeZero;
            for (int k = 1; k <= 2; k++) {
                assertTickAt(resetAt + k * PERIOD, ticks.take(), timeZero, k);
            }
            tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
            Thread.sleep(100);
            while (ticks.poll(0) != null) {
                // a tick sent before the stop arrived
            }
            assertNull(ticks.poll(PERIOD / MS + 100), "no tick after the run stopped");
        }
    }

    @Test
    void aTickerInItsOwnJvmWithItsClock120MsBehindTicksAtTheTestersRunTimes(@TempDir Path dir) throws Exception {
        String cluster = TestClusters.uniqueName("runClockTickerJvm");
        int port = FreePorts.range(FreePorts.BUS_RANGE);
        Dtron tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("tester").tester(true)
                .port(port).portRange(FreePorts.BUS_RANGE).build());
        try (ChildJvm child = ChildJvm.start(RunClockTickerMain.class, dir.resolve("ticker.log"), cluster, "ticker",
                "correct", "-120", "1", Integer.toString(port))) {
            child.awaitOutput("joined", Duration.ofSeconds(60));
            Inbox ticks = new Inbox(TICK);
            Inbox starts = new Inbox(Dtron.RUN_START);
            tester.addDtronListener(ticks);
            tester.addDtronListener(starts);
            // the ticker estimates its offset from the tester's hello; its ticks say when it has one
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
            boolean estimated = false;
            while (!estimated) {
                tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 20_000)));
                long timeZero = starts.take().getEventTimeNanos();
                IDtronChannelValued first = ticks.take();
                estimated = first.getClockErrorNanos() > 0;
                if (estimated) {
                    assertTickAt(PERIOD, first, timeZero, 1);
                    assertTickAt(2 * PERIOD, ticks.take(), timeZero, 2);
                    assertTrue(Math.abs(first.getClockOffsetNanos() - 120 * MS) <= first.getClockErrorNanos(),
                            first.getClockOffsetNanos() + " +/- " + first.getClockErrorNanos());
                }
                tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
                Thread.sleep(PERIOD / MS);
                while (ticks.poll(0) != null) {
                    // ticks of that run
                }
                assertTrue(System.nanoTime() < deadline, "no offset estimate: " + child.output());
            }
            tester.close();
            assertEquals(0, child.waitFor(Duration.ofSeconds(30)), child.output());
        } finally {
            tester.close();
        }
    }
}
