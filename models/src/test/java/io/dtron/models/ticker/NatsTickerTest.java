package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.Waits;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The ticker through a NATS bus ({@code dtron run --bus nats://...} on a nats-server of the test's): the Java bus
 * adapter, the Python adapter ({@code clients/python/examples/ticker.py}) and the C adapter each pass, and their slow
 * variants fail. The Python adapter runs with {@code $DTRON_PYTHON} (a Python with the {@code dtron} package
 * installed; {@code scripts/test} makes one), else {@code python3} if it has the package. Python and C members
 * without the bus's secret, on the bus through a whole run, change nothing.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class NatsTickerTest {
    static final String MODEL = "src/main/resources/io/dtron/models/ticker.xml";

    @TempDir
    Path dir;

    /**
     * A dtron run of the ticker model on the NATS bus, in this JVM: 60 time units of 100 ms, so that the model's
     * tolerance of 2 units (200 ms) holds for a fresh Python or JVM on a loaded machine (stalls of 100 ms were seen
     * with both cores busy), and a slow ticker (13 units, 1 beyond the tolerance) is still late.
     */
    record Run(int exit, String out, String err) {
        static Run of(String url, String cluster, String... more) {
            List<String> args = new java.util.ArrayList<>(List.of(MODEL, "--bus", url, "--cluster", cluster,
                    "--timeunit", "100000", "--timeout", "60", "--delay-policy", "eager", "--wait-timeout", "60"));
            args.addAll(List.of(more));
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            int exit = DtronCommand.run(args.toArray(String[]::new), new PrintWriter(out, true),
                    new PrintWriter(err, true));
            return new Run(exit, out.toString(), err.toString());
        }

        String shown() {
            return "exit " + exit + "\n" + out + err;
        }
    }

    static String cluster(String what) {
        return what + "-" + UUID.randomUUID().toString().substring(0, 8);
    }

    @Test
    void theJavaBusAdapterPassesOnNatsAndItsSlowVariantFails() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            Run passed = Run.of(server.url(), cluster("java"), "--adapter", TickerBusAdapter.class.getName());
            assertEquals(0, passed.exit(), passed.shown());
            assertTrue(passed.out().contains("PASSED"), passed.shown());
            assertTrue(passed.out().contains("on bus '") && passed.out().contains(server.url()), passed.shown());
            Run failed = Run.of(server.url(), cluster("java-slow"), "--adapter",
                    TickerBusAdapter.class.getName() + ":slow");
            assertEquals(2, failed.exit(), failed.shown());
            assertTrue(failed.out().contains("FAILED"), failed.shown());
        }
    }

    /** Starts an adapter process for one run on the bus; its output goes to a log in the test's folder. */
    Process adapter(String name, List<String> command) throws Exception {
        return new ProcessBuilder(command).redirectErrorStream(true)
                .redirectOutput(dir.resolve(name + ".log").toFile()).start();
    }

    String log(String name) throws Exception {
        return java.nio.file.Files.readString(dir.resolve(name + ".log"));
    }

    /** Runs the tester against an adapter process; returns the run, with the adapter's log when it went wrong. */
    Run against(NatsServer server, String name, List<String> command) throws Exception {
        String cluster = cluster(name);
        List<String> full = new java.util.ArrayList<>(command);
        full.addAll(List.of("--bus", server.url(), "--cluster", cluster, "--runs", "1"));
        Process process = adapter(name, full);
        try {
            Run run = Run.of(server.url(), cluster);
            assertTrue(process.waitFor(30, TimeUnit.SECONDS), "the adapter exits after its run:\n" + log(name));
            return new Run(run.exit(), run.out(), run.err() + "\nadapter " + name + ":\n" + log(name));
        } finally {
            process.destroyForcibly();
        }
    }

    @Test
    void thePythonAdapterPassesOnNatsAndItsSlowVariantFails() throws Exception {
        String python = NatsClients.python();
        Path ticker = NatsClients.PYTHON.resolve("examples/ticker.py").toAbsolutePath().normalize();
        try (NatsServer server = NatsServer.start(dir)) {
            Run passed = against(server, "py", List.of(python, ticker.toString()));
            assertEquals(0, passed.exit(), passed.shown());
            assertTrue(passed.out().contains("PASSED"), passed.shown());
            Run failed = against(server, "py-slow", List.of(python, ticker.toString(), "--variant", "slow"));
            assertEquals(2, failed.exit(), failed.shown());
            assertTrue(failed.out().contains("FAILED"), failed.shown());
        }
    }

    @Test
    void theCAdapterPassesOnNatsAndItsSlowVariantFails() throws Exception {
        String ticker = NatsClients.cProgram("dtron-ticker").toString();
        try (NatsServer server = NatsServer.start(dir)) {
            Run passed = against(server, "c", List.of(ticker));
            assertEquals(0, passed.exit(), passed.shown());
            assertTrue(passed.out().contains("PASSED"), passed.shown());
            Run failed = against(server, "c-slow", List.of(ticker, "--variant", "slow"));
            assertEquals(2, failed.exit(), failed.shown());
            assertTrue(failed.out().contains("FAILED"), failed.shown());
        }
    }

    /**
     * A stranger in Python: the dtron package with a key file of its own (not the bus's), publishing {@code
     * tick(seq=1)} every 50 ms for 30 s, far longer than the run. argv: server, bus, key file.
     */
    private static final String FORGER = """
            import asyncio, sys
            import dtron

            async def main(url, bus, key_file):
                async with await dtron.connect(url, bus=bus, key_file=key_file) as member:
                    tick = dtron.Channel("tick", "seq")
                    member.declare_outputs(tick)
                    print("forging as", member.member, flush=True)
                    for _ in range(600):
                        await member.send(tick.value(seq=1))
                        await asyncio.sleep(0.05)

            asyncio.run(main(sys.argv[1], sys.argv[2], sys.argv[3]))
            """;

    @Test
    void membersWithoutTheSecretInPythonAndCCannotChangeTheVerdict() throws Exception {
        // the correct Python ticker has the bus's secret (DTRON_HOME, inherited); a Python forger of ticks and a C
        // ticker hold another key: were their messages taken, the forged ticks would FAIL the run ("too early") or
        // end it INCONCLUSIVE as a second owner of tick; without the secret they are dropped, and the run PASSES
        String python = NatsClients.python();
        Path ticker = NatsClients.PYTHON.resolve("examples/ticker.py").toAbsolutePath().normalize();
        Path stranger = dir.resolve("stranger.key");
        Files.writeString(stranger, "f".repeat(64) + "\n");
        Files.setPosixFilePermissions(stranger, PosixFilePermissions.fromString("rw-------"));
        Path forger = Files.writeString(dir.resolve("forger.py"), FORGER);
        try (NatsServer server = NatsServer.start(dir)) {
            String cluster = cluster("strangers");
            Process forging = adapter("forger", List.of(python, forger.toString(), server.url(), cluster,
                    stranger.toString()));
            Process cTicker = adapter("c-stranger", List.of(NatsClients.cProgram("dtron-ticker").toString(),
                    "--bus", server.url(), "--cluster", cluster, "--key-file", stranger.toString()));
            Process pyTicker = adapter("py", List.of(python, ticker.toString(), "--bus", server.url(), "--cluster",
                    cluster, "--runs", "1"));
            try {
                Waits.await("the forger publishes").atMost(java.time.Duration.ofSeconds(60))
                        .until(() -> log("forger").contains("forging as"));
                Run run = Run.of(server.url(), cluster);
                String shown = run.shown() + "\nforger:\n" + log("forger") + "\nC stranger:\n" + log("c-stranger");
                assertEquals(0, run.exit(), shown);
                assertTrue(run.out().contains("PASSED"), shown);
                assertTrue(run.out().contains("unauthenticated"), shown);
                assertTrue(forging.isAlive(), "the forger was still forging at the verdict: " + shown);
            } finally {
                forging.destroyForcibly();
                cTicker.destroyForcibly();
                pyTicker.destroyForcibly();
            }
        }
    }

    @Test
    void aBusThatCannotBeReachedIsOneLine() throws Exception {
        Run run = Run.of("nats://127.0.0.1:" + NatsServer.freePort(), cluster("none"), "--adapter",
                TickerBusAdapter.class.getName());
        assertEquals(1, run.exit(), run.shown());
        assertEquals(1, run.err().strip().lines().count(), run.shown());
        assertTrue(run.err().startsWith("dtron run: cannot join bus"), run.shown());
    }
}
