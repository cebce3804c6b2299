package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.LogCapture;
import io.dtron.testsupport.TickerRunBounds;
import io.dtron.testsupport.Waits;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.time.Duration;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** The ticker as a bus adapter: on its own on the bus, and tested by the README's command. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class TickerBusAdapterTest {
    private static final IDtronChannel FLUSHED = IDtronChannel.of("flushed");
    private final String cluster = "ticker-" + UUID.randomUUID().toString().substring(0, 8);

    @Test
    void ticksFromTheStartOfARunAndRestartsOnReset() throws Exception {
        BlockingQueue<IDtronChannelValued> ticks = new LinkedBlockingQueue<>();
        try (Dtron tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build());
                Dtron bus = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build());
                TickerBusAdapter ticker = new TickerBusAdapter()) {
            ticker.start(bus);
            tester.addDtronListener(new DtronListener(TickerBusAdapter.TICK) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    ticks.add(message);
                }
            });
            assertTrue(tester.awaitMembers(2, Duration.ofSeconds(10)));
            // The ticker counts the period from the publish time, which send sets: the clock starts before it.
            long start = System.nanoTime();
            tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 2000)));
            assertEquals(1, seq(ticks));
            long first = (System.nanoTime() - start) / 1_000_000;
            assertTrue(first >= 15, "the first tick comes 10 time units (20 ms) after the start, not " + first);
            assertEquals(2, seq(ticks));
            tester.send(TickerBusAdapter.RESET.constructValued(Map.of()));
            // ticks due before the reset reached the ticker (how many is the machine's business) go on counting
            int next = seq(ticks);
            for (int old = 3; next == old; old++) {
                next = seq(ticks);
            }
            assertEquals(1, next, "a reset restarts the numbering");
            tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
            // once the ticker's run clock stopped, its member sends a marker: the bus keeps a member's order, so every
            // tick sent before arrived before the marker
            Waits.await("the ticker's run clock stopped").until(() -> !bus.runClock().isRunning());
            CountDownLatch flushed = new CountDownLatch(1);
            tester.addDtronListener(new DtronListener(FLUSHED) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    flushed.countDown();
                }
            });
            bus.send(FLUSHED.constructValued(Map.of()));
            assertTrue(flushed.await(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS));
            ticks.clear();
            // a tick under way when the run stopped finishes (however long load holds up its thread); none starts
            if (ticks.poll(100, TimeUnit.MILLISECONDS) != null) {
                assertNull(ticks.poll(100, TimeUnit.MILLISECONDS), "no tick after the end of the run");
            }
            tester.send(TickerBusAdapter.RESET.constructValued(Map.of()));
            assertNull(ticks.poll(100, TimeUnit.MILLISECONDS), "a reset between runs starts nothing");
            tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 2000)));
            assertEquals(1, seq(ticks), "the next run starts the ticks again");
        }
    }

    @Test
    void unknownVariantsAreRefused() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> new TickerBusAdapter("fast"));
        assertEquals("unknown variant 'fast' of io.dtron.models.ticker.TickerBusAdapter; known variants: correct,"
                + " slow", e.getMessage());
        assertEquals("slow", new TickerBusAdapter("slow").variant());
    }

    @Test
    void theReadmeCommandPassesUnlessTheMachineHeldItUpAndTheSlowVariantFails() {
        String[] readme = {"src/main/resources/io/dtron/models/ticker.xml", "--adapter",
                TickerBusAdapter.class.getName(), "--timeunit", "10000", "--timeout", "300", "--delay-policy", "eager",
                "--cluster", cluster};
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        try (LogCapture ticker = new LogCapture(TickerBusAdapter.class)) {
            int exit = DtronCommand.run(readme, new PrintWriter(out), new PrintWriter(err));
            // at 10 ms per unit a busy machine can hold the ticker's JVM up beyond the model's 2 units: then FAILED is
            // right, and the ticker, timing its ticks on its own run clock, says it was late; or hold the tester up:
            // then INCONCLUSIVE, in the tester's own words. A FAILED verdict for a tick sent on time would be a false
            // one, and fails this test, as does an INCONCLUSIVE for another reason.
            TickerRunBounds.assertPassedUnlessHeldUp(exit, out + "" + err, 300,
                    () -> String.join("\n", ticker.messages()));
        }

        readme[2] = TickerBusAdapter.class.getName() + ":slow";
        readme[readme.length - 1] = cluster + "-slow";
        StringWriter slow = new StringWriter();
        assertEquals(2, DtronCommand.run(readme, new PrintWriter(slow), new PrintWriter(new StringWriter())),
                slow.toString());
        // the slow ticker's first tick, at 13 on the run's clock, is judged at that time
        TickerRunBounds.assertSlowTickerFailed(slow.toString());
    }

    private static int seq(BlockingQueue<IDtronChannelValued> ticks) throws InterruptedException {
        IDtronChannelValued tick = ticks.poll(10, TimeUnit.SECONDS);
        assertNotNull(tick, "no tick within 10 s");
        return tick.getVariables().get("seq");
    }
}
