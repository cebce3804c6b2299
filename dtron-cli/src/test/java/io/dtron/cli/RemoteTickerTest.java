package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.api.ClockOffset;
import io.dtron.api.DtronOptions;
import io.dtron.bridge.BusBridge;
import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.testadapter.RunClockTickerMain;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Waits;
import java.nio.file.Path;
import java.time.Duration;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * A ticker on the run clock in a JVM of its own: with its clock 2 s off either way it passes, and the tester
 * reports its offset within the estimate's error bound; when it goes silent mid-run (its JVM stopped or killed) it
 * is named in an INCONCLUSIVE verdict, and the system behind it is not blamed with FAILED for the deadline it could
 * not meet.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class RemoteTickerTest {
    private static final String TICKER = """
            chan i_reset, o_tick;
            int[0,999] o_tick_seq;
            process Ticker() { clock x; state Running { x <= 12 }; init Running;
                trans Running -> Running { guard x >= 8; sync o_tick!; assign o_tick_seq = (o_tick_seq + 1) % 1000,
                        x = 0; },
                      Running -> Running { sync i_reset?; assign x = 0, o_tick_seq = 0; }; }
            process Env() { clock e; state Watching; init Watching;
                trans Watching -> Watching { guard e >= 25; sync i_reset!; assign e = 0; },
                      Watching -> Watching { sync o_tick?; }; }
            system Ticker, Env;
            """;

    @TempDir
    Path dir;

    private void silenced(boolean kill) throws Exception {
        Network network = ModelLoader.load("ticker.xta", TICKER);
        TestInterface testInterface = TestInterface.fromNames(network);
        String cluster = "silent-" + UUID.randomUUID().toString().substring(0, 8);
        String member = "ticker-" + UUID.randomUUID().toString().substring(0, 8);
        int port = FreePorts.range(FreePorts.BUS_RANGE);
        try (BusBridge bridge = BusBridge.connect(testInterface, DtronOptions.builder().clusterName(cluster)
                .port(port).portRange(FreePorts.BUS_RANGE));
                ChildJvm ticker = ChildJvm.start(RunClockTickerMain.class, dir.resolve("ticker.log"), cluster, member,
                        "correct", "0", "1", Integer.toString(port))) {
            ticker.awaitOutput("joined", Duration.ofSeconds(60));
            assertTrue(bridge.run().awaitAdapters(1, Duration.ofSeconds(30)));
            ticker.awaitOutput("offset", Waits.TIMEOUT);
            // 100 ms per unit: the model's 2 units of jitter, 200 ms, hold for a ticker JVM on a busy machine (at 25 ms
            // one was seen held up 225 ms)
            TestOptions options = new TestOptions(1, 100_000, 1000, DelayPolicy.RANDOM, 0, false, 50_000);
            CompletableFuture<TestResult> run = CompletableFuture.supplyAsync(
                    () -> new OnlineTester(network, testInterface, bridge, options).run());
            // it goes silent once the run judged some of its ticks
            Waits.await("ticks of the run").until(() -> bridge.run().outputLatency().count() >= 3);
            if (kill) {
                ticker.kill();
            } else {
                ticker.suspend();
            }
            TestResult result = run.get(60, TimeUnit.SECONDS);
            if (!kill) {
                ticker.resume();
            }
            assertEquals(Verdict.INCONCLUSIVE, result.verdict(), result.explanation() + "\n" + ticker.output());
            assertTrue(result.explanation().contains(member), result.explanation());
            // the 3 ticks received before it went silent came during the run, so were judged
            assertTrue(result.outputs() >= 3, "it ticked before it went silent: " + result);
        }
    }

    @Test
    void anAdapterWhoseClockIsOffTwoSecondsPassesAndEstimatesItsOffset() throws Exception {
        Network network = ModelLoader.load("ticker.xta", TICKER);
        TestInterface testInterface = TestInterface.fromNames(network);
        String cluster = "shifted-" + UUID.randomUUID().toString().substring(0, 8);
        for (String shift : new String[] {"2000", "-2000"}) {
            int port = FreePorts.range(FreePorts.BUS_RANGE);
            try (BusBridge bridge = BusBridge.connect(testInterface, DtronOptions.builder().clusterName(cluster)
                    .port(port).portRange(FreePorts.BUS_RANGE));
                    ChildJvm ticker = ChildJvm.start(RunClockTickerMain.class, dir.resolve("shifted" + shift + ".log"),
                            cluster, "shifted-ticker", "correct", shift, "1", Integer.toString(port))) {
                ticker.awaitOutput("joined", Duration.ofSeconds(60));
                assertTrue(bridge.run().awaitAdapters(1, Duration.ofSeconds(30)));
                ticker.awaitOutput("offset", Waits.TIMEOUT);
                // 250 ms per unit: a clock 2 s off, uncorrected, would put every tick 8 units away from where the
                // tester expects it, beyond the model's tolerance of 2 (500 ms, which a busy machine keeps)
                TestOptions options = new TestOptions(1, 250_000, 40, DelayPolicy.EAGER, 0, false, 50_000);
                TestResult result = new OnlineTester(network, testInterface, bridge, options).run();
                assertEquals(Verdict.PASSED, result.verdict(), result.explanation() + "\n" + ticker.output());
                // the invariant x <= 12 forces 2 ticks in the 25 units or more before each reset, and 3 in 40 units
                // without one
                assertTrue(result.outputs() >= 2 * result.inputs() && result.outputs() >= 2, result.toString());
                // the tester's clock minus the ticker's: minus the shift, within the estimate's error bound
                ClockOffset offset = bridge.run().clockOffsets().get("shifted-ticker");
                long expected = -Long.parseLong(shift) * 1_000_000;
                assertTrue(offset != null && Math.abs(offset.offsetNanos() - expected) <= offset.errorNanos(),
                        "offset " + offset + ", expected " + expected + " ns");
            }
        }
    }

    @Test
    void aStoppedAdapterIsNamedAndTheRunIsInconclusive() throws Exception {
        silenced(false);
    }

    @Test
    void aKilledAdapterIsNamedAndTheRunIsInconclusive() throws Exception {
        silenced(true);
    }
}
