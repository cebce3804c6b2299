package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.testadapter.BusTicker;
import io.dtron.testadapter.TickerAdapterMain;
import io.dtron.testsupport.BusSummary;
import io.dtron.testsupport.TickerRunBounds;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code java -jar dtron.jar MODEL} in one JVM tests the bundled ticker model against ticker adapters in other
 * JVMs, which use only {@code io.dtron.api}. Runs after the jar is built ({@code mvn verify}).
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class DtronJarIT {
    private static final Path JAR = Path.of("target", "dtron.jar");
    private static final Path TICKER = Path.of("..", "models", "src", "main", "resources", "io", "dtron", "models",
            "ticker.xml");
    private static final Duration WAIT = Duration.ofSeconds(60);

    @TempDir
    Path dir;

    private final String cluster = "it-" + UUID.randomUUID().toString().substring(0, 8);

    /**
     * dtron.jar on the ticker model, with resets as early as allowed. The runs that expect PASSED use 100 ms per
     * time unit: the model tolerates 2 units of jitter, 200 ms, which a freshly started adapter JVM keeps on a busy
     * 2-core machine (at 25 ms its first tick came 88 ms late there, at 10 ms later still).
     */
    private ChildJvm dtron(int adapters, String... options) throws Exception {
        List<String> args = new ArrayList<>(List.of(TICKER.toString(), "--cluster", cluster, "--wait-for-adapters",
                String.valueOf(adapters), "--delay-policy", "eager", "--seed", "1"));
        args.addAll(List.of(options));
        return ChildJvm.startJar(JAR, dir.resolve("dtron.log"), args.toArray(new String[0]));
    }

    private ChildJvm adapter(String variant) throws Exception {
        return ChildJvm.start(TickerAdapterMain.class, dir.resolve("adapter.log"), cluster, "ticker-adapter", variant,
                "1");
    }

    @Test
    void aCorrectAdapterInAnotherJvmPasses() throws Exception {
        try (ChildJvm dtron = dtron(1, "--timeunit", "100000", "--timeout", "100");
                ChildJvm adapter = adapter("correct")) {
            assertEquals(0, dtron.waitFor(WAIT), dtron.output());
            String out = dtron.output();
            assertTrue(out.contains("dtron run: members [") && out.contains("ticker-adapter"), out);
            int inputs = TickerRunBounds.assertPassed(out, 100);
            assertTrue(out.contains("latency t2 - t1 of inputs back from the bus: count "), out);
            BusSummary.assertNothingOfTheRunRejected(out);
            assertTrue(out.contains(", listener failures 0"), out);
            assertEquals(0, adapter.waitFor(WAIT), adapter.output());
            // the bus keeps the tester's order: the adapter saw every input before the tester left
            assertTrue(adapter.output().contains("resets " + inputs), "the inputs reached the adapter: "
                    + adapter.output());
        }
    }

    @Test
    void aSlowAdapterInAnotherJvmFails() throws Exception {
        try (ChildJvm dtron = dtron(1, "--timeunit", "25000", "--timeout", "200");
                ChildJvm adapter = adapter("slow")) {
            assertEquals(2, dtron.waitFor(WAIT), dtron.output());
            String out = dtron.output();
            // the tick due by 12 comes at 13 by the adapter's clock, within the reorder window: judged at its time
            TickerRunBounds.assertSlowTickerFailed(out);
            assertTrue(out.contains("latency t2 - t1 of outputs: "), out);
            assertEquals(0, adapter.waitFor(WAIT), adapter.output());
        }
    }

    @Test
    void badMessagesOfARogueMemberAreRejectedCountedAndTheRunGoesOn() throws Exception {
        try (ChildJvm dtron = dtron(2, "--timeunit", "100000", "--timeout", "100");
                ChildJvm adapter = adapter("correct");
                ChildJvm rogue = ChildJvm.start(RogueMemberMain.class, dir.resolve("rogue.log"), cluster)) {
            assertEquals(0, dtron.waitFor(WAIT), dtron.output() + rogue.output());
            String out = dtron.output();
            assertTrue(rogue.output().contains("sent 4"), rogue.output());
            TickerRunBounds.assertPassed(out, 100);
            // the rogue sent its 4 messages 300 ms into a run of 10 s, and the tester counts each as it arrives; frames
            // without the bus's code from other processes probing the same ports may be counted too (see BusSummary)
            Matcher rejected = Pattern.compile(", rejected (\\d+) \\(malformed 1, unknown channel 1, unknown variables 1,"
                    + " missing variables 1(?:, unauthenticated (\\d+))?\\), listener failures 0").matcher(out);
            assertTrue(rejected.find(), out);
            assertEquals(4 + (rejected.group(2) == null ? 0 : Long.parseLong(rejected.group(2))),
                    Long.parseLong(rejected.group(1)), out);
            assertTrue(out.contains("Rejected a message on channel 'tick' from rogue (3 bytes), MALFORMED"), out);
            assertTrue(out.contains("Rejected a message on channel 'bogus' from rogue"), out);
            assertTrue(out.contains("UNKNOWN_VARIABLES: channel tick has no variable colour"), out);
            assertTrue(out.contains("MISSING_VARIABLES: channel tick needs variable seq"), out);
            assertFalse(out.contains("\tat "), "no stack traces: " + out);
        }
    }

    @Test
    void anAdapterThatDiesMidRunEndsItInconclusiveNamingTheMember() throws Exception {
        // half a second per time unit: the first tick is due 5 s into the run, long after the adapter is noticed gone
        try (ChildJvm dtron = dtron(1, "--timeunit", "500000", "--timeout", "100");
                ChildJvm adapter = adapter("correct")) {
            dtron.awaitOutput("dtron run: members [", WAIT);
            Thread.sleep(300);
            adapter.kill();
            assertEquals(3, dtron.waitFor(WAIT), dtron.output());
            String out = dtron.output();
            // it may leave before the run starts (the tester waited for it) or during the run: INCONCLUSIVE either way
            // (before the start, it names the channels it leaves unserved)
            Matcher verdict = Pattern.compile("INCONCLUSIVE: adapter member ticker-adapter left the bus"
                    + "(?: before the run started)? \\(members now \\[[^]]+]\\)"
                    + "(?:, and no adapter serves input reset, output tick any more)?;"
                    + " the system under test may be gone \\(at t=(\\d+)\\.\\d+\\)").matcher(out);
            // how soon the member was noticed gone is the machine's business; the verdict is not FAILED either way
            assertTrue(verdict.find(), out);
            assertTrue(out.contains("statistics: 1 INCONCLUSIVE 0 0 "), out);
        }
    }

    /**
     * The README's quick start, with a bus adapter in the tester's JVM: the run ends without a stack trace. Members
     * that leave the bus used to log JGroups' "failed handling message ... Stream closed" with one, in 1 run of 3 to
     * 8; six runs at once on their own buses.
     */
    @Test
    void aBusRunWithAnAdapterInTheSameJvmEndsWithoutAStackTrace() throws Exception {
        String adapterClasses = Path.of(BusTicker.class.getProtectionDomain().getCodeSource().getLocation().toURI())
                .toString();
        List<ChildJvm> runs = new ArrayList<>();
        try {
            for (int i = 0; i < 6; i++) {
                runs.add(ChildJvm.startJar(JAR, dir.resolve("quick-start-" + i + ".log"), TICKER.toString(),
                        "--cluster", cluster + "-" + i, "--classpath", adapterClasses, "--adapter",
                        BusTicker.class.getName(), "--timeunit", "25000", "--timeout", "40", "--delay-policy",
                        "eager"));
            }
            for (ChildJvm run : runs) {
                run.waitFor(WAIT);
                String out = run.output();
                assertTrue(out.contains("statistics: "), "the run ended: " + out);
                assertFalse(out.contains("\tat ") || out.contains("Exception"), "no stack trace: " + out);
            }
        } finally {
            runs.forEach(ChildJvm::close);
        }
    }

    @Test
    void theJarTakesAModelAloneAndRejectsUnknownOptionsSayingWhereTheHelpIs() throws Exception {
        try (ChildJvm dtron = ChildJvm.startJar(JAR, dir.resolve("dtron.log"), TICKER.toString(), "--bogus")) {
            assertEquals(1, dtron.waitFor(WAIT), dtron.output());
            assertTrue(dtron.output().contains("Unknown option: '--bogus'"), dtron.output());
            assertTrue(dtron.output().contains("see 'dtron run --help'"), dtron.output());
            assertFalse(dtron.output().contains("Usage:"), "not the whole usage: " + dtron.output());
        }
    }
}
