package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.CommandRun;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/** {@code dtron tron}: TRON's command line, with TRON's sample setup and every usage error. */
@Timeout(value = 120, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronCommandTest {
    private static Path lightContr;

    @TempDir
    Path dir;

    @BeforeAll
    static void find() throws Exception {
        lightContr = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron", "LightContr.xml");
        Warmup.lightContr(io.dtron.model.ModelLoader.load(lightContr));
    }

    private static CommandRun tron(String... args) {
        String[] withCommand = new String[args.length + 1];
        withCommand[0] = "tron";
        System.arraycopy(args, 0, withCommand, 1, args.length);
        return CommandRun.of(withCommand);
    }

    /** TRON's sample: the lamp listens, the tester connects, with delays -P 10,200 and -F 300. */
    private CommandRun sample(String variant, String... extra) throws Exception {
        try (ChildProcess lamp = ChildProcess.start(LampIutMain.class, dir.resolve("lamp.log"), "listen",
                "REAL_TIME", variant, "300", Integer.toString(TronLampEndToEndTest.REAL_TIME_UNIT))) {
            int port = lamp.awaitPort(Duration.ofSeconds(30));
            String[] head = {"-I", "SocketAdapter", "-P", "10,200", "-F", "300", "-X", "42"};
            String[] tail = {lightContr.toString(), "--", "127.0.0.1", Integer.toString(port)};
            String[] args = new String[head.length + extra.length + tail.length];
            System.arraycopy(head, 0, args, 0, head.length);
            System.arraycopy(extra, 0, args, head.length, extra.length);
            System.arraycopy(tail, 0, args, head.length + extra.length, tail.length);
            CommandRun r = tron(args);
            assertEquals(0, lamp.waitFor(Duration.ofSeconds(30)), lamp.output());
            return r;
        }
    }

    @Test
    void tronsSampleSetupPassesTheCorrectLampWithStatisticsAndALog() throws Exception {
        Path stats = dir.resolve("stats.txt");
        Path log = dir.resolve("tron.log");
        CommandRun r = sample("correct", "-v", "2", "-S", stats.toString(), "-o", log.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("random seed 42, connecting to 127.0.0.1:"), r.out());
        assertTrue(r.out().contains("300 time units of 10000 us; inputs grasp(), release(); outputs level(adapLevel)"),
                r.out());
        assertTrue(r.out().contains(" input grasp()"), r.out());
        assertTrue(r.out().contains("TEST PASSED: the timeout of 300 time units was reached"), r.out());
        assertFalse(r.err().contains("note: -P"), r.err()); // applied as TRON applies it
        assertTrue(Files.readString(stats).matches("42 PASSED \\d+ \\d+ 30\\d{5}\\R"), Files.readString(stats));
        assertEquals(r.out(), Files.readString(log).replace(System.lineSeparator(), "\n"));
    }

    @Test
    void tronsSampleSetupFailsTheLateLampWithExitCode2() throws Exception {
        CommandRun r = sample("late", "-q");
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().startsWith("TEST FAILED: "), r.out());
        assertEquals(1, r.out().lines().count(), r.out());
    }

    @Test
    void listensForTheAdapterInVirtualTime() throws Exception {
        int port;
        try (ServerSocket probe = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            port = probe.getLocalPort();
        }
        CompletableFuture<CommandRun> run = CompletableFuture.supplyAsync(() -> tron("--virtual-time", "-X", "9", "-F",
                "3000", lightContr.toString(), "--", Integer.toString(port)));
        TronLamp.runWhenListening(port);
        CommandRun r = run.get(60, TimeUnit.SECONDS);
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("dtron tron: waiting for the adapter on 127.0.0.1:" + port), r.out());
        assertTrue(r.out().contains("3000 time units of 1000 us"), r.out());
        assertTrue(r.out().contains("TEST PASSED"), r.out());
    }

    @Test
    void anUnwritableTraceOrStatisticsFileIsAClearError() throws Exception {
        Path trace = dir.resolve("no-such-folder").resolve("trace.jsonl");
        CommandRun noTrace = withLampInVirtualTime("--trace", trace.toString());
        assertEquals(1, noTrace.exit(), noTrace.out() + noTrace.err());
        assertTrue(noTrace.err().contains("dtron tron: cannot write the trace " + trace + ": "), noTrace.err());
        CommandRun noStats = withLampInVirtualTime("-S", dir.toString());
        assertEquals(1, noStats.exit(), noStats.out() + noStats.err());
        assertTrue(noStats.out().contains("TEST PASSED"), noStats.out());
        assertTrue(noStats.err().contains("dtron tron: cannot write the statistics " + dir + ": "), noStats.err());
        assertFalse((noTrace.err() + noStats.err()).contains("\tat "), "no stack trace");
    }

    /** Runs dtron tron listening, with the lamp connecting in virtual time; the lamp may be cut off. */
    private CommandRun withLampInVirtualTime(String... options) throws Exception {
        int port;
        try (ServerSocket probe = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            port = probe.getLocalPort();
        }
        String[] args = new String[options.length + 7];
        System.arraycopy(options, 0, args, 0, options.length);
        System.arraycopy(new String[] {"--virtual-time", "-X", "9", "-F", "300", lightContr.toString(), "--"}, 0,
                args, options.length, 7);
        String[] withPort = java.util.Arrays.copyOf(args, args.length + 1);
        withPort[args.length] = Integer.toString(port);
        CompletableFuture<CommandRun> run = CompletableFuture.supplyAsync(() -> tron(withPort));
        try {
            TronLamp.runWhenListening(port);
        } catch (RuntimeException e) {
            // the tester ended the connection when it could not go on
        }
        return run.get(60, TimeUnit.SECONDS);
    }

    @Test
    void aProtocolErrorDuringTheTestIsInconclusiveWithExitCode3() throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            CompletableFuture<Void> adapter = CompletableFuture.runAsync(() -> {
                try (var socket = server.accept(); RawClient c = RawClient.over(socket)) {
                    c.configureLamp(5000).int32(77).uint16(0);
                    c.closedByTester();
                } catch (IOException e) {
                    throw new IllegalStateException(e);
                }
            });
            CommandRun r = tron(lightContr.toString(), "--", "127.0.0.1", Integer.toString(server.getLocalPort()));
            adapter.get(10, TimeUnit.SECONDS);
            assertEquals(3, r.exit(), r.out() + r.err());
            assertTrue(r.out().contains("TEST INCONCLUSIVE: protocol error: the adapter sent an event on channel id"
                    + " 77, which was never registered"), r.out());
        }
    }

    @Test
    void aBrokenConfigurationIsAUsageError() throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            CompletableFuture<Void> adapter = CompletableFuture.runAsync(() -> {
                try (var socket = server.accept(); RawClient c = RawClient.over(socket)) {
                    c.bytes(42);
                    c.closedByTester();
                } catch (IOException e) {
                    throw new IllegalStateException(e);
                }
            });
            CommandRun r = tron(lightContr.toString(), "--", "127.0.0.1", Integer.toString(server.getLocalPort()));
            adapter.get(10, TimeUnit.SECONDS);
            assertEquals(1, r.exit(), r.out() + r.err());
            assertTrue(r.err().contains("dtron tron: the adapter's configuration failed: unknown command byte 42"),
                    r.err());
        }
    }

    @Test
    void aRunLongerThanDtronCanTimeIsRefusedToTheAdapterAndEndsWithTheReason() throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            CompletableFuture<String> adapter = CompletableFuture.supplyAsync(() -> {
                try (var socket = server.accept(); RawClient c = RawClient.over(socket)) {
                    c.bytes(1).string("grasp");
                    assertEquals(1, c.readInt());
                    c.bytes(5).int32(0).int32(1000);
                    assertEquals(0, c.readInt());
                    c.bytes(64);
                    String reply = c.readString();
                    assertTrue(c.closedByTester());
                    return reply;
                } catch (IOException e) {
                    throw new IllegalStateException(e);
                }
            });
            CommandRun r = tron("-F", Long.toString(Long.MAX_VALUE), lightContr.toString(), "--", "127.0.0.1",
                    Integer.toString(server.getLocalPort()));
            String reason = "the timeout of 9223372036854775807 time units of 1000 us is longer than DTRON can time: at"
                    + " most 9223372036854775 us (about 292 years) (timeout from -F, time unit from the adapter)";
            assertEquals("DTRON refuses the start: " + reason, adapter.get(10, TimeUnit.SECONDS));
            assertEquals(1, r.exit(), r.out() + r.err());
            assertTrue(r.err().contains("dtron tron: " + reason), r.err());
            assertFalse(r.err().contains("Exception") || r.err().contains("\tat "), "no stack trace: " + r.err());
        }
    }

    @Test
    void anAdapterConfiguringARunLongerThanDtronCanTimeGetsAnErrorCodeAndTheRunEndsWithTheReason()
            throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            CompletableFuture<Integer> adapter = CompletableFuture.supplyAsync(() -> {
                try (var socket = server.accept(); RawClient c = RawClient.over(socket)) {
                    c.bytes(1).string("grasp");
                    assertEquals(1, c.readInt());
                    c.bytes(5).int32(0).int32(Integer.MAX_VALUE);
                    assertEquals(0, c.readInt());
                    c.bytes(6).int32(Integer.MAX_VALUE);
                    int code = c.readInt();
                    c.bytes(64);
                    c.readString();
                    return code;
                } catch (IOException e) {
                    throw new IllegalStateException(e);
                }
            });
            CommandRun r = tron(lightContr.toString(), "--", "127.0.0.1", Integer.toString(server.getLocalPort()));
            assertEquals(-13, adapter.get(10, TimeUnit.SECONDS));
            assertEquals(1, r.exit(), r.out() + r.err());
            assertTrue(r.err().contains("dtron tron: the adapter's configuration failed: the test was not started: 1"
                    + " registration was refused: timeout 2147483647: the timeout of 2147483647 time units of"
                    + " 2147483647 us is longer than DTRON can time"), r.err());
            assertFalse(r.err().contains("Exception") || r.err().contains("\tat "), "no stack trace: " + r.err());
        }
    }

    @Test
    void anInterfaceTheEngineRefusesIsTheReplyToTheAdaptersStart() throws Exception {
        for (boolean tronCommandLine : new boolean[] {true, false}) {
            try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
                CompletableFuture<String> adapter = CompletableFuture.supplyAsync(() -> {
                    try (var socket = server.accept(); RawClient c = RawClient.over(socket)) {
                        // release left out: the model's processes no longer split into an environment and a system
                        c.bytes(1).string("grasp");
                        assertEquals(1, c.readInt());
                        c.bytes(2).string("level");
                        assertEquals(2, c.readInt());
                        c.bytes(64);
                        String reply = c.readString();
                        assertTrue(c.closedByTester());
                        return reply;
                    } catch (IOException e) {
                        throw new IllegalStateException(e);
                    }
                });
                String port = Integer.toString(server.getLocalPort());
                CommandRun r = tronCommandLine ? tron(lightContr.toString(), "--", "127.0.0.1", port)
                        : CommandRun.of("run", lightContr.toString(), "--tron-adapter", "127.0.0.1:" + port);
                String reply = adapter.get(10, TimeUnit.SECONDS);
                assertEquals(1, r.exit(), r.out() + r.err());
                assertTrue(reply.startsWith("DTRON refuses the start: "), reply);
                String reason = reply.substring("DTRON refuses the start: ".length());
                assertTrue(reason.length() > 20, reply);
                assertTrue(r.err().contains(reason.endsWith("...") ? reason.substring(0, reason.length() - 3)
                        : reason), r.err());
            }
        }
    }

    @Test
    void aSilentPeerEndsTheConfigurationAfterConfigTimeoutAskingWhatListens() throws Exception {
        try (SilentPeer peer = new SilentPeer()) {
            long start = System.nanoTime();
            CommandRun r = tron("--config-timeout", "1", lightContr.toString(), "--", "127.0.0.1",
                    Integer.toString(peer.port()));
            long took = (System.nanoTime() - start) / 1_000_000;
            peer.awaitHangUp();
            assertEquals(1, r.exit(), r.out() + r.err());
            assertTrue(r.err().contains("the adapter sent nothing for 1 s during configuration"), r.err());
            assertTrue(r.err().contains("is something else listening on port " + peer.port() + "?"),
                    r.err());
            // not before the 1 s asked; the 10 s default would take 10 s at least
            assertTrue(took >= 1000 && took < 10_000, "took " + took + " ms, not the 1 s asked");
        }
    }

    @Test
    void dashUpperQTakesTheClockPortAsTronsDoesAndDashQIsQuiet() throws Exception {
        CommandRun modelAsPort = tron("-Q", lightContr.toString(), "--", "9999");
        assertEquals(1, modelAsPort.exit());
        assertTrue(modelAsPort.err().contains("-Q takes the port of TRON's virtual clock server (0 to 65535), as"
                + " TRON's does; for quiet output use -q"), modelAsPort.err());
        try (ServerSocket taken = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            CommandRun busy = tron("-qQ", Integer.toString(taken.getLocalPort()), lightContr.toString(), "--",
                    "9999");
            assertEquals(1, busy.exit());
            assertTrue(busy.err().contains("-Q " + taken.getLocalPort() + ": cannot serve the virtual clock on"
                    + " 127.0.0.1:" + taken.getLocalPort()), busy.err());
            assertFalse(busy.err().contains("\tat "), busy.err());
        }
    }

    /** Keeps both cores busy until closed: the machine of a loaded CI run. */
    static final class Load implements AutoCloseable {
        private final java.util.concurrent.atomic.AtomicBoolean on = new java.util.concurrent.atomic.AtomicBoolean(true);
        private final List<Thread> threads = new java.util.ArrayList<>();

        Load(int threads) {
            for (int i = 0; i < threads; i++) {
                Thread t = new Thread(() -> {
                    long x = 0;
                    while (on.get()) {
                        x += System.nanoTime() % 7;
                    }
                    if (x == 42) {
                        System.out.print("");
                    }
                }, "load-" + i);
                t.setDaemon(true);
                t.start();
                this.threads.add(t);
            }
        }

        @Override
        public void close() throws InterruptedException {
            on.set(false);
            for (Thread t : threads) {
                t.join();
            }
        }
    }

    @Test
    void lazyInputsComeAsLateAsCanStillBeMetWithBothCoresBusy() throws Exception {
        // 10 ms per unit: a margin that misses the load's scheduling delay (milliseconds) aims past the end of a window
        Path stats = dir.resolve("lazy-stats.txt");
        CommandRun r;
        try (ChildProcess lamp = ChildProcess.start(LampIutMain.class, dir.resolve("lazy-lamp.log"), "listen",
                "REAL_TIME", "correct", "600", Integer.toString(TronLampEndToEndTest.REAL_TIME_UNIT));
             Load load = new Load(2)) {
            int port = lamp.awaitPort(Duration.ofSeconds(30));
            r = tron("-P", "lazy", "-X", "13", "-F", "600", "-S", stats.toString(), lightContr.toString(), "--",
                    "127.0.0.1", Integer.toString(port));
            lamp.waitFor(Duration.ofSeconds(30));
        }
        // the margin is measured, not guessed: the tester says how late its thread woke up and what it leaves
        java.util.regex.Matcher m = java.util.regex.Pattern.compile("wakes up to ([0-9.]+) ms late here; inputs are"
                + " aimed at least ([0-9.]+) ms").matcher(r.out());
        assertTrue(m.find(), r.out());
        assertTrue(Double.parseDouble(m.group(2)) >= Math.max(2.0, 2 * Double.parseDouble(m.group(1))) - 0.001,
                r.out());
        assertFalse(r.out().contains("could not be applied") || r.out().contains("executed too late"),
                "every lazy input was applied inside its window: " + r.out() + r.err());
        // at least the first grasp, which lazy holds back to the end of its window (100 units wide); the lamp's own
        // outputs may come late on a machine this busy and end the run FAILED after it, which is not this test's point
        String[] line = Files.readString(stats).strip().split(" ");
        assertTrue(Integer.parseInt(line[2]) >= 1, "inputs: " + Files.readString(stats) + r.out());
    }

    @Test
    void usageErrorsSayWhatIsWrong() throws Exception {
        String model = lightContr.toString();
        CommandRun otherAdapter = tron("-I", "TraceAdapter", model, "--", "9999");
        assertEquals(1, otherAdapter.exit());
        assertTrue(otherAdapter.err().contains("-I TraceAdapter is not supported: DTRON speaks TRON's socket adapter"
                + " protocol only"), otherAdapter.err());
        CommandRun badDelay = tron("-P", "200,10", model, "--", "9999");
        assertEquals(1, badDelay.exit());
        assertTrue(badDelay.err().contains("-P 200,10: use random, eager, lazy, MAX or SHORT,LONG"), badDelay.err());
        CommandRun unknown = tron("-Z", "1", model, "--", "9999");
        assertEquals(1, unknown.exit());
        assertTrue(unknown.err().contains("Unknown option: '-Z'"), unknown.err());
        CommandRun noAddress = tron(model);
        assertEquals(1, noAddress.exit());
        assertTrue(noAddress.err().contains("give the adapter's address after the model"), noAddress.err());
        CommandRun badPort = tron(model, "--", "localhost", "port");
        assertEquals(1, badPort.exit());
        assertTrue(badPort.err().contains("'port' is not a port"), badPort.err());
        CommandRun tooMany = tron(model, "--", "localhost", "1", "2");
        assertEquals(1, tooMany.exit());
        assertTrue(tooMany.err().contains("too many arguments after the model"), tooMany.err());
        CommandRun badUncertainty = tron("-U", "x", model, "--", "1");
        assertEquals(1, badUncertainty.exit());
        assertTrue(badUncertainty.err().contains("-U x: give a number"), badUncertainty.err());
        CommandRun longReplyTimeout = tron("--virtual-time", "--reply-timeout", Long.toString(Long.MAX_VALUE), model, "--",
                "1");
        assertEquals(1, longReplyTimeout.exit());
        assertTrue(longReplyTimeout.err().contains("--reply-timeout must be a positive number of seconds, at most"
                + " 9223372036 (about 292 years)"), longReplyTimeout.err());
        for (CommandRun r : List.of(otherAdapter, badDelay, unknown, noAddress, badPort, tooMany, badUncertainty,
                longReplyTimeout)) {
            assertTrue(r.err().startsWith("dtron tron: "), r.err());
            assertTrue(r.err().endsWith("see 'dtron tron --help'" + System.lineSeparator()), r.err());
            assertFalse(r.err().contains("Usage:"), "not the whole usage: " + r.err());
        }
        CommandRun missingModel = tron(dir.resolve("none.xml").toString(), "--", "1");
        assertEquals(1, missingModel.exit());
        assertTrue(missingModel.err().contains("none.xml"), missingModel.err());
    }

    @Test
    void nobodyListeningIsAUsageError() throws Exception {
        int port;
        try (ServerSocket probe = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            port = probe.getLocalPort();
        }
        CommandRun r = tron("-U", "5", lightContr.toString(), "--", "127.0.0.1", Integer.toString(port));
        assertEquals(1, r.exit());
        assertTrue(r.err().contains("cannot connect to the adapter at 127.0.0.1:" + port), r.err());
        assertTrue(r.err().contains("note: -U 5 is accepted and not applied"), r.err());
        assertFalse(r.out().contains("TEST"), r.out());
    }
}
