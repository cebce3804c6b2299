package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * DTRON in TRON's place against a test adapter in another JVM ({@link LampIutMain}) that registers LightContr's
 * interface with {@link TronAdapterClient}: a correct lamp passes and a late one fails, in real time and with the
 * shared virtual clock; both sides of the protocol run over real sockets.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronLampEndToEndTest {
    /**
     * Microseconds per model time unit in real-time runs: LightContr's tolerances are 5 units, and 10 ms per unit
     * leaves room for a busy machine's scheduling delays (a run of 300 units takes 3 s).
     */
    static final int REAL_TIME_UNIT = 10_000;
    private static Network lightContr;

    @TempDir
    Path dir;

    @BeforeAll
    static void load() throws Exception {
        Path tron = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        lightContr = ModelLoader.load(tron.resolve("LightContr.xml"));
        Warmup.lightContr(lightContr);
    }

    /** The tester listens on an ephemeral port and the lamp connects. */
    private TestResult testerListens(String mode, String variant, boolean virtual, long seed, int timeout, int unit)
            throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress());
             ChildProcess lamp = ChildProcess.start(LampIutMain.class, dir.resolve("lamp-" + seed + ".log"),
                     "connect", Integer.toString(server.getLocalPort()), mode, variant, Integer.toString(timeout),
                     Integer.toString(unit))) {
            server.setSoTimeout(30_000);
            TronSocketAdapter adapter = TronSocketAdapter.accept(server, lightContr,
                    TronSocketAdapter.Settings.forRealTime().withVirtualTime(virtual));
            TestResult result = run(adapter, virtual, seed, timeout, unit);
            assertEquals(0, lamp.waitFor(Duration.ofSeconds(30)), lamp.output());
            assertTrue(lamp.output().contains("END"), lamp.output());
            return result;
        }
    }

    /** The lamp listens, as in TRON's samples, and the tester connects. */
    private TestResult lampListens(String mode, String variant, boolean virtual, long seed, int timeout)
            throws Exception {
        try (ChildProcess lamp = ChildProcess.start(LampIutMain.class, dir.resolve("lamp-" + seed + ".log"),
                "listen", mode, variant, Integer.toString(timeout), "1000")) {
            int port = lamp.awaitPort(Duration.ofSeconds(30));
            TronSocketAdapter adapter = TronSocketAdapter.connect("127.0.0.1", port, lightContr,
                    TronSocketAdapter.Settings.forRealTime().withVirtualTime(virtual));
            TestResult result = run(adapter, virtual, seed, timeout, 1000);
            assertEquals(0, lamp.waitFor(Duration.ofSeconds(30)), lamp.output());
            return result;
        }
    }

    private static TestResult run(TronSocketAdapter adapter, boolean virtual, long seed, int timeout, int unit) {
        TestInterface ti = adapter.testInterface();
        assertEquals(List.of("grasp", "release"), ti.inputs().stream().map(TestInterface.ObservableChannel::name)
                .toList());
        assertEquals("adapLevel", ti.outputs().get(0).variables().get(0).name());
        assertEquals((long) unit, ti.timeUnitMicros());
        assertEquals((long) timeout, ti.timeout());
        assertEquals(virtual, adapter.sharedVirtualClock());
        TestOptions options = new TestOptions(seed, ti.timeUnitMicros(), ti.timeout(), DelayPolicy.RANDOM, 0,
                virtual);
        StringBuilder timeline = new StringBuilder();
        TestResult result = new OnlineTester(lightContr, ti, adapter, options).addListener(new TestListener() {
            @Override
            public void inputApplied(Event input, long micros) {
                timeline.append(micros).append(" us: input ").append(input).append('\n');
            }

            @Override
            public void outputObserved(Event output, long micros) {
                timeline.append(micros).append(" us: output ").append(output).append('\n');
            }
        }).run();
        return new TestResult(result.verdict(), result.explanation() + "\ntimeline:\n" + timeline, result.seed(),
                result.inputs(), result.outputs(), result.durationMicros());
    }

    @Test
    void theCorrectLampPassesInRealTime() throws Exception {
        TestResult result = testerListens("REAL_TIME", "correct", false, 11, 300, REAL_TIME_UNIT);
        assertEquals(Verdict.PASSED, result.verdict(), result.explanation());
        assertTrue(result.outputs() > 0, result.statisticsLine());
    }

    @Test
    void theLateLampFailsInRealTime() throws Exception {
        TestResult result = testerListens("REAL_TIME", "late", false, 12, 300, REAL_TIME_UNIT);
        assertEquals(Verdict.FAILED, result.verdict(), result.explanation());
        assertTrue(result.explanation().contains("level"), result.explanation());
    }

    @Test
    void theCorrectLampPassesWithTheSharedVirtualClockAndTheRunIsReproducible() throws Exception {
        TestResult first = lampListens("SHARED_VIRTUAL_CLOCK", "correct", true, 21, 5000);
        assertEquals(Verdict.PASSED, first.verdict(), first.explanation());
        assertTrue(first.inputs() > 10 && first.outputs() > 10, first.statisticsLine());
        TestResult again = lampListens("SHARED_VIRTUAL_CLOCK", "correct", true, 21, 5000);
        assertEquals(first.statisticsLine(), again.statisticsLine());
    }

    @Test
    void theLateLampFailsWithTheSharedVirtualClock() throws Exception {
        TestResult result = testerListens("SHARED_VIRTUAL_CLOCK", "late", true, 22, 5000, 1000);
        assertEquals(Verdict.FAILED, result.verdict(), result.explanation());
        assertTrue(result.explanation().contains("level"), result.explanation());
    }
}
