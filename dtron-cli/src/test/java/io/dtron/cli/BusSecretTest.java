package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.dtron.api.ChildJvm;
import io.dtron.testadapter.BusTicker;
import io.dtron.testsupport.BusSummary;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.ListeningSockets;
import io.dtron.testsupport.ListeningSockets.Listener;
import io.dtron.testsupport.RecordingProxy;
import io.dtron.testsupport.TickerRunBounds;
import io.dtron.testsupport.Waits;
import java.io.ByteArrayOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The bus's secret on real processes: {@code dtron run} of the bundled ticker model with a ticker bus adapter in the
 * same JVM (the README's quick start), both with the default key file (the build's {@code DTRON_HOME}), on free
 * ports, and a stranger in a JVM of its own without the secret (a key file of its own) forging ticks and resets all
 * along. The run passes, the
 * stranger is never a member, what it sends never reaches the tester (its frames are counted in the run's summary as
 * unauthenticated, and nothing else is rejected), and it cannot hold the bus up even when it started first on the
 * bus's first port. Frames announcing 2 GB and random bytes on every listening port of the run's members leave the
 * verdict as it was, the tester's heap under 200 MB (its {@code -Xmx}), and no stack trace. Connections between the
 * members recorded on the way (a proxy on a bus port) and sent again to every listening port during the run are
 * counted as replayed and change nothing. An insecure tester says so and does not hear a secure member.
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class BusSecretTest {
    private static final Path TICKER = Path.of("..", "models", "src", "main", "resources", "io", "dtron", "models",
            "ticker.xml");
    private static final Duration WAIT = Duration.ofSeconds(90);
    /**
     * The heap the tester and the adapter may use (a frame believed to hold 2 GB would not fit), and the logging of
     * {@code dtron.jar} (what its console shows, not the tests' logging).
     */
    private static final List<String> JVM_OPTIONS = List.of("-Xmx200m", "-Dlogback.configurationFile="
            + Path.of("target", "classes", "logback.xml").toAbsolutePath());
    private static final String DROPPED = "dropped a frame from";
    private static final String REPLAYED = "began a connection recorded earlier";

    @TempDir
    Path dir;

    private final String cluster = "secret-" + UUID.randomUUID().toString().substring(0, 8);
    private final int port = FreePorts.range(FreePorts.BUS_RANGE);

    /**
     * The ticker run with the ticker's bus adapter in the tester's JVM, at 100 ms per time unit for 100 units: the
     * model tolerates 2 units of jitter, 200 ms, which a busy machine keeps (as DtronJarIT's runs that expect PASSED).
     */
    private ChildJvm dtron(String... more) throws IOException {
        List<String> args = new ArrayList<>(List.of("run", TICKER.toString(), "--cluster", cluster, "--port",
                Integer.toString(port), "--port-range", Integer.toString(FreePorts.BUS_RANGE), "--adapter",
                BusTicker.class.getName(), "--wait-for-adapters", "1", "--delay-policy", "eager", "--seed", "1",
                "--timeunit", "100000", "--timeout", "100"));
        args.addAll(List.of(more));
        return ChildJvm.start(JVM_OPTIONS, DtronCommand.class, dir.resolve("dtron.log"), args.toArray(new String[0]));
    }

    /** A stranger with a key file of its own, mode 600: another secret. */
    private ChildJvm stranger() throws IOException {
        Path key = dir.resolve("stranger.key");
        if (!Files.exists(key)) {
            Files.writeString(key, "not-the-bus-secret\n");
            Files.setPosixFilePermissions(key, PosixFilePermissions.fromString("rw-------"));
        }
        return member("stranger", key.toString());
    }

    /** A member in a JVM of its own that forges ticks and resets (see {@link StrangerMain}). */
    private ChildJvm member(String log, String key) throws IOException {
        return ChildJvm.start(JVM_OPTIONS, StrangerMain.class, dir.resolve(log + ".log"), cluster,
                Integer.toString(port), Integer.toString(FreePorts.BUS_RANGE), key);
    }

    /**
     * The run passed (unless a busy machine held the ticker or the tester up, which they say), heard nothing of the
     * stranger, printed no stack trace and at most one line of dropped frames.
     */
    private static void assertPassedUntouched(ChildJvm dtron, ChildJvm stranger) throws Exception {
        int exit = dtron.waitFor(WAIT);
        String out = dtron.output();
        // the ticker in the tester's JVM says in its log, the same output, when a busy machine held it up
        TickerRunBounds.assertPassedUnlessHeldUp(exit, out, 100, dtron::output);
        BusSummary.assertNothingOfTheRunRejected(out); // the stranger's frames, dropped, are unauthenticated
        assertFalse(out.contains("stranger"), "the stranger is never a member: " + out);
        assertQuiet(out);
        if (stranger != null) {
            for (String line : stranger.output().lines().filter(l -> l.startsWith("members ")).toList()) {
                assertEquals("members [stranger]", line, "the stranger sees no one: " + stranger.output());
            }
        }
    }

    private static void assertQuiet(String out) {
        assertFalse(out.contains("\tat ") || out.contains("Exception"), "no stack trace: " + out);
        List<String> dropped = out.lines().filter(l -> l.contains(DROPPED)).toList();
        assertTrue(dropped.stream().filter(l -> l.contains(REPLAYED)).count() <= 1
                && dropped.stream().filter(l -> !l.contains(REPLAYED)).count() <= 1, "one line at most a reason: " + out);
    }

    @Test
    void aStrangerForgingTicksAndResetsDuringTheRunIsNeitherSeenNorHeard() throws Exception {
        try (ChildJvm dtron = dtron()) {
            dtron.awaitOutput("dtron run: members [", WAIT);
            try (ChildJvm stranger = stranger()) {
                stranger.awaitOutput("members [", WAIT);
                assertPassedUntouched(dtron, stranger);
                // the stranger's discovery reached the tester's port when it joined: dropped and counted
                assertTrue(BusSummary.assertNothingOfTheRunRejected(dtron.output()) > 0,
                        "the stranger's frames are counted: " + dtron.output());
            }
        }
    }

    @Test
    void aSquatterThatStartedFirstOnTheBusPortsHoldsNoOneUp() throws Exception {
        try (ChildJvm squatter = stranger()) {
            squatter.awaitOutput("members [", WAIT);
            try (ChildJvm dtron = dtron()) {
                assertPassedUntouched(dtron, squatter);
            }
        }
    }

    @Test
    void hugeFramesAndGarbageOnEveryListeningPortChangeNothing() throws Exception {
        assumeTrue(ListeningSockets.available(), "needs Linux's /proc");
        try (ChildJvm dtron = dtron()) {
            dtron.awaitOutput("dtron run: members [", WAIT);
            List<Integer> ports = ListeningSockets.of(dtron.toHandle().pid()).stream().map(Listener::port).toList();
            assertEquals(2, ports.size(), "the tester and its adapter listen: " + ports);
            byte[] garbage = new byte[64 * 1024];
            new Random(23).nextBytes(garbage);
            for (int listening : ports) {
                sendQuietly(listening, hugeFrame());
                sendQuietly(listening, garbage);
            }
            assertPassedUntouched(dtron, null);
        }
    }

    @Test
    void connectionsBetweenTheMembersRecordedAndSentAgainChangeNothing() throws Exception {
        assumeTrue(ListeningSockets.available(), "needs Linux's /proc");
        // the last bus port: the members probe it when they join, and it takes them to the first member's port
        try (RecordingProxy proxy = new RecordingProxy(port + FreePorts.BUS_RANGE, port);
                ChildJvm dtron = dtron()) {
            dtron.awaitOutput("dtron run: members [", WAIT);
            Waits.await("a recorded connection").until(() -> !recordedWithHello(proxy).isEmpty());
            List<Integer> ports = ListeningSockets.of(dtron.toHandle().pid()).stream().map(Listener::port).toList();
            assertEquals(2, ports.size(), "the tester and its adapter listen: " + ports);
            for (byte[] connection : recordedWithHello(proxy)) {
                for (int listening : ports) {
                    sendQuietly(listening, connection);
                }
            }
            int exit = dtron.waitFor(WAIT);
            String out = dtron.output();
            TickerRunBounds.assertPassedUnlessHeldUp(exit, out, 100, dtron::output);
            // besides frames of other processes on the ports without the secret (see BusSummary), if any
            Matcher summary = Pattern.compile("(?m)^bus: published \\d+, accepted \\d+, rejected \\d+ "
                    + "\\((unauthenticated \\d+, )?replayed [1-9]\\d*\\), ").matcher(out);
            assertTrue(summary.find(), "the replays the tester dropped are counted as replayed: " + out);
            assertTrue(out.contains(REPLAYED), "one line says so: " + out);
            assertQuiet(out);
        }
    }

    /** The connections the proxy recorded that hold at least a hello: its length (84) and itself. */
    private static List<byte[]> recordedWithHello(RecordingProxy proxy) {
        return proxy.recorded().stream().filter(c -> c.length >= 88 && c[0] == 0 && c[1] == 0 && c[2] == 0
                && c[3] == 84).toList();
    }

    /** 78 bytes: a length of 2 GB - 1, and the start of what it announces. */
    private static byte[] hugeFrame() throws IOException {
        ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        DataOutputStream out = new DataOutputStream(bytes);
        out.writeInt(Integer.MAX_VALUE);
        out.write(new byte[74]);
        return bytes.toByteArray();
    }

    private static void sendQuietly(int port, byte[] bytes) {
        try (Socket socket = new Socket()) {
            socket.connect(new InetSocketAddress("127.0.0.1", port), 2_000);
            socket.getOutputStream().write(bytes);
            socket.getOutputStream().flush();
        } catch (IOException e) {
            // the member closed the connection before it took everything: what it should do
        }
    }

    @Test
    void aKeyFileOthersMayReadStopsTheRunWithTheLineCliMdShows() throws Exception {
        String shown = DocPage.read("cli.md").blockAfter("stops the command with one line (exit 1):").code().strip();
        Path key = Files.writeString(dir.resolve("bus.key"), "s3cret\n");
        Files.setPosixFilePermissions(key, PosixFilePermissions.fromString("rw-r--r--"));
        // the page's bus: the key file is read before any socket is opened
        CommandRun run = CommandRun.of("run", TICKER.toString(), "--key-file", key.toString(), "--wait-timeout", "1");
        assertEquals(1, run.exit(), run.out() + run.err());
        assertEquals(shown.replace("/home/ann/bus.key", key.toString()), run.err().strip());
        CommandRun both = CommandRun.of("run", TICKER.toString(), "--key-file", key.toString(), "--insecure");
        assertEquals(1, both.exit(), both.err());
        assertTrue(both.err().startsWith("dtron run: --insecure uses no secret: leave out --key-file"), both.err());
    }

    @Test
    void anInsecureTesterSaysSoAndDoesNotHearASecureMember() throws Exception {
        try (ChildJvm secure = member("secure", "--default")) {
            secure.awaitOutput("members [", WAIT);
            List<String> args = List.of("run", TICKER.toString(), "--cluster", cluster, "--port",
                    Integer.toString(port), "--port-range", Integer.toString(FreePorts.BUS_RANGE), "--insecure",
                    "--wait-for-adapters", "1", "--wait-timeout", "5");
            try (ChildJvm dtron = ChildJvm.start(JVM_OPTIONS, DtronCommand.class, dir.resolve("dtron.log"),
                    args.toArray(new String[0]))) {
                assertEquals(1, dtron.waitFor(WAIT), dtron.output());
                String out = dtron.output();
                assertTrue(out.contains("INSECURE: member "), "the warning: " + out);
                assertFalse(out.contains("stranger"), "the secure member is never a member of its bus: " + out);
                assertFalse(out.contains("\tat "), out);
            }
            for (String line : secure.output().lines().filter(l -> l.startsWith("members ")).toList()) {
                assertEquals("members [stranger]", line, "the insecure tester is never a member: " + secure.output());
            }
        }
    }
}
