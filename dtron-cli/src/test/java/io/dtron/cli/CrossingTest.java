package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
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
import io.dtron.testsupport.FreePorts;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * An output that crosses an input on the bus is judged where it happened: the system of {@code crossing.xta},
 * behind an adapter in a JVM of its own, produces x just before input y reaches it, and x reaches the tester after
 * the tester sent y (held up 5 ms between stamping and sending). Judged by arrival, the correct system would fail
 * every run; judged by event times (x's stamp, y's acknowledgement) it is never failed, and the same adapter with
 * x truly after y fails every run that saw x. A busy machine may hold up the tester or a message beyond what the
 * model's windows or the reorder window allow (INCONCLUSIVE, saying so), or x beyond the run's end (PASSED without
 * outputs): never a wrong verdict. Real time, 10 ms per unit, both on one bus for many runs.
 */
@Timeout(value = 5, unit = TimeUnit.MINUTES)
class CrossingTest {
    /** Runs per variant; scripts/verdict-stats.sh style soak runs go further outside the test command. */
    private static final int RUNS = 50;

    @TempDir
    Path dir;

    private Map<Verdict, List<String>> runs(String variant) throws Exception {
        String model;
        try (InputStream in = CrossingTest.class.getResourceAsStream("crossing.xta")) {
            model = new String(in.readAllBytes(), StandardCharsets.UTF_8);
        }
        Network network = ModelLoader.load("crossing.xta", model);
        TestInterface testInterface = TestInterface.fromNames(network);
        String cluster = "crossing-" + UUID.randomUUID().toString().substring(0, 8);
        Path log = dir.resolve(variant + ".log");
        Map<Verdict, List<String>> verdicts = new TreeMap<>();
        int port = FreePorts.range(FreePorts.BUS_RANGE);
        try (BusBridge bridge = BusBridge.connect(testInterface, DtronOptions.builder().clusterName(cluster)
                .port(port).portRange(FreePorts.BUS_RANGE));
                ChildJvm adapter = ChildJvm.start(CrossingAdapterMain.class, log, cluster, variant,
                        Integer.toString(port))) {
            adapter.awaitOutput("ready", Duration.ofSeconds(60));
            for (int seed = 1; seed <= RUNS; seed++) {
                // y as early as allowed (t=10): the crossing adapter applies it about 6 ms (0.6 units) after it came
                TestOptions options = new TestOptions(seed, 10_000, 25, DelayPolicy.EAGER, 0, false, 50_000);
                TestResult result = new OnlineTester(network, testInterface, bridge, options).run();
                verdicts.computeIfAbsent(result.verdict(), v -> new ArrayList<>()).add(seed + ": "
                        + result.explanation());
            }
        } finally {
            if (Files.exists(log)) {
                System.out.println(variant + " adapter: " + Files.readString(log));
            }
        }
        return verdicts;
    }

    /**
     * Asserts that the runs that were not judged were INCONCLUSIVE because a busy machine held up the tester or a
     * message (an input too late for its window, a message beyond the reorder window): never judged, never wrong.
     */
    private static void assertHeldUpOnly(Map<Verdict, List<String>> verdicts) {
        assertTrue(verdicts.getOrDefault(Verdict.INCONCLUSIVE, List.of()).stream()
                .allMatch(r -> r.contains("too late") || r.contains("more than the reorder window")), verdicts.toString());
    }

    @Test
    void anOutputThatCrossedAnInputOnTheBusIsNeverFailed() throws Exception {
        Map<Verdict, List<String>> verdicts = runs("crossing");
        assertEquals(List.of(), verdicts.getOrDefault(Verdict.FAILED, List.of()), verdicts.toString());
        assertHeldUpOnly(verdicts);
        assertTrue(verdicts.containsKey(Verdict.PASSED), verdicts.toString());
    }

    @Test
    void anOutputTrulyAfterTheInputFailsEveryRunThatSawIt() throws Exception {
        Map<Verdict, List<String>> verdicts = runs("late");
        // a run passes only when x had not come by its end (the machine held up the adapter's thread that long)
        assertTrue(verdicts.getOrDefault(Verdict.PASSED, List.of()).stream().allMatch(r -> r.contains(" and 0 outputs")),
                verdicts.toString());
        assertTrue(verdicts.getOrDefault(Verdict.FAILED, List.of()).stream()
                .allMatch(r -> r.contains("output x() observed at t=")), verdicts.toString());
        assertHeldUpOnly(verdicts);
        assertTrue(verdicts.containsKey(Verdict.FAILED), verdicts.toString());
    }
}
