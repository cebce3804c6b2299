package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.NatsServer;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Path;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The ticker through a NATS bus ({@code dtron run --bus nats://...} on a nats-server of the test's): the Java bus
 * adapter passes and its slow variant fails.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class NatsTickerTest {
    static final String MODEL = "src/main/resources/io/dtron/models/ticker.xml";

    @TempDir
    Path dir;

    /** A dtron run of the ticker model on the NATS bus, in this JVM. */
    record Run(int exit, String out, String err) {
        static Run of(String url, String cluster, String... more) {
            List<String> args = new java.util.ArrayList<>(List.of(MODEL, "--bus", url, "--cluster", cluster,
                    "--timeunit", "10000", "--timeout", "300", "--delay-policy", "eager", "--wait-timeout", "60"));
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

    @Test
    void aBusThatCannotBeReachedIsOneLine() throws Exception {
        Run run = Run.of("nats://127.0.0.1:" + NatsServer.freePort(), cluster("none"), "--adapter",
                TickerBusAdapter.class.getName());
        assertEquals(1, run.exit(), run.shown());
        assertEquals(1, run.err().strip().lines().count(), run.shown());
        assertTrue(run.err().startsWith("dtron run: cannot join bus"), run.shown());
    }
}
