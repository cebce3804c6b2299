package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.CommandRun;
import io.dtron.cli.DtronCommand;
import io.dtron.testadapter.BusTicker;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.stream.Collectors;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron run} with TRON's protocol: {@code --tron-adapter} tests an adapter written for TRON with DTRON's
 * engine in TRON's place; {@code --backend tron} has an installed TRON judge DTRON's system under test (here a
 * {@code tron} script that runs DTRON in TRON's place, in a JVM of its own).
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class RunWithTronTest {
    private static Path tronModels;
    private static Path lightContr;

    @TempDir
    Path dir;

    @BeforeAll
    static void find() throws Exception {
        tronModels = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron").toAbsolutePath();
        lightContr = tronModels.resolve("LightContr.xml");
        Warmup.lightContr(io.dtron.model.ModelLoader.load(lightContr));
    }

    /** The lamp's adapter listens, as in TRON's sample; dtron run connects to it. */
    private CommandRun againstListeningLamp(String variant) throws Exception {
        try (ChildProcess lamp = ChildProcess.start(LampIutMain.class, dir.resolve("lamp.log"), "listen",
                "REAL_TIME", variant, "300", Integer.toString(TronLampEndToEndTest.REAL_TIME_UNIT))) {
            int port = lamp.awaitPort(Duration.ofSeconds(30));
            CommandRun r = CommandRun.of("run", lightContr.toString(), "--tron-adapter", "127.0.0.1:" + port, "--seed", "7",
                    "--delay-policy", "random-bounded", "--delay-bound", "200");
            assertEquals(0, lamp.waitFor(Duration.ofSeconds(30)), lamp.output());
            return r;
        }
    }

    @Test
    void theCorrectTronAdapterPasses() throws Exception {
        CommandRun r = againstListeningLamp("correct");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("against the TRON adapter at 127.0.0.1:"), r.out());
        assertTrue(r.out().contains("seed 7, 300 time units of " + TronLampEndToEndTest.REAL_TIME_UNIT + " us"),
                r.out());
        assertTrue(r.out().contains("\nPASSED: the timeout of 300 time units was reached"), r.out());
    }

    @Test
    void aFaultyTronAdapterFails() throws Exception {
        CommandRun r = againstListeningLamp("late");
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("\nFAILED: "), r.out());
        assertTrue(r.out().contains("level"), r.out());
    }

    @Test
    void listensForTheTronAdapterInVirtualTime() throws Exception {
        int port = freePort();
        CommandRun r = withLampConnecting(port, "run", lightContr.toString(), "--tron-adapter", Integer.toString(port),
                "--virtual-time", "--timeout", "3000", "--seed", "3");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("dtron run: waiting for the TRON adapter on 127.0.0.1:" + port), r.out());
        assertTrue(r.out().contains("3000 time units of 1000 us in virtual time"), r.out());
        assertTrue(r.out().contains("\nPASSED: "), r.out());
    }

    @Test
    void listensWhereBindSays() throws Exception {
        int port = freePort();
        CommandRun r = withLampConnecting(port, "run", lightContr.toString(), "--tron-adapter", Integer.toString(port),
                "--bind", "0.0.0.0", "--virtual-time", "--timeout", "1000", "--seed", "3");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("dtron run: waiting for the TRON adapter on 0.0.0.0:" + port), r.out());
        assertTrue(r.out().contains("\nPASSED: "), r.out());
    }

    private static int freePort() throws IOException {
        try (ServerSocket probe = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            return probe.getLocalPort();
        }
    }

    /** Runs dtron, which listens on {@code port}, and the lamp in this JVM, which connects as soon as it can. */
    private CommandRun withLampConnecting(int port, String... args) throws Exception {
        CompletableFuture<CommandRun> run = CompletableFuture.supplyAsync(() -> CommandRun.of(args));
        TronLamp.runWhenListening(port);
        return run.get(60, TimeUnit.SECONDS);
    }

    @Test
    void aSilentTronAdapterEndsTheConfigurationAfterConfigTimeout() throws Exception {
        try (SilentPeer peer = new SilentPeer()) {
            long start = System.nanoTime();
            CommandRun r = CommandRun.of("run", lightContr.toString(), "--tron-adapter",
                    "127.0.0.1:" + peer.port(), "--config-timeout", "1");
            long took = (System.nanoTime() - start) / 1_000_000;
            peer.awaitHangUp();
            assertEquals(1, r.exit(), r.out() + r.err());
            assertTrue(r.err().contains("the adapter sent nothing for 1 s during configuration"), r.err());
            // not before the 1 s asked; the 10 s default would take 10 s at least
            assertTrue(took >= 1000 && took < 10_000, "took " + took + " ms, not the 1 s asked");
        }
    }

    @Test
    void tronAdapterTimeoutsNeedATronAdapterAndPositiveValues() {
        String model = lightContr.toString();
        CommandRun withoutAdapter = CommandRun.of("run", model, "--config-timeout", "3");
        assertEquals(1, withoutAdapter.exit());
        assertTrue(withoutAdapter.err().contains("--config-timeout and --reply-timeout are for the adapter of"
                + " --tron-adapter"), withoutAdapter.err());
        CommandRun zero = CommandRun.of("run", model, "--tron-adapter", "9999", "--reply-timeout", "0");
        assertEquals(1, zero.exit());
        assertTrue(zero.err().contains("--reply-timeout must be a positive number of seconds"), zero.err());
    }

    @Test
    void tronAdapterOptionsThatCannotGoTogetherAreUsageErrors() throws Exception {
        String model = lightContr.toString();
        CommandRun withSut = CommandRun.of("run", model, "--tron-adapter", "9999", "--sut", LampSystem.class.getName());
        assertEquals(1, withSut.exit());
        assertTrue(withSut.err().contains("--sut and --tron-adapter each name the system under test"), withSut.err());
        CommandRun withInterface = CommandRun.of("run", model, "--tron-adapter", "9999", "--interface",
                tronModels.resolve("LightContr.trn").toString());
        assertEquals(1, withInterface.exit());
        assertTrue(withInterface.err().contains("the adapter's configuration defines the interface: leave out"
                + " --interface"), withInterface.err());
        CommandRun withTron = CommandRun.of("run", model, "--tron-adapter", "localhost:9999", "--backend", "tron");
        assertEquals(1, withTron.exit());
        assertTrue(withTron.err().contains("leave out --backend tron"), withTron.err());
        CommandRun withBus = CommandRun.of("run", model, "--tron-adapter", "9999", "--cluster", "x");
        assertEquals(1, withBus.exit());
        assertTrue(withBus.err().contains("are for testing the adapters on a bus"), withBus.err());
        CommandRun bindToConnect = CommandRun.of("run", model, "--tron-adapter", "localhost:9999", "--bind", "0.0.0.0");
        assertEquals(1, bindToConnect.exit());
        assertTrue(bindToConnect.err().contains("--bind is the bus's network interface, or where --tron-adapter PORT"
                + " listens; with --tron-adapter HOST:PORT (DTRON connects) leave it out"), bindToConnect.err());
        CommandRun unknownBind = CommandRun.of("run", model, "--tron-adapter", "9999", "--bind", "no-such-host.invalid");
        assertEquals(1, unknownBind.exit());
        assertTrue(unknownBind.err().contains("--bind: unknown address 'no-such-host.invalid'"), unknownBind.err());
        for (String bad : List.of("host:", "localhost:port", "70000", "localhost:0", ":80")) {
            CommandRun r = CommandRun.of("run", model, "--tron-adapter", bad);
            assertEquals(1, r.exit(), bad);
            assertTrue(r.err().contains("--tron-adapter " + bad + ": give HOST:PORT to connect to the adapter, or"
                    + " PORT to listen for it"), r.err());
        }
        CommandRun badBackend = CommandRun.of("run", model, "--backend", "uppaal");
        assertEquals(1, badBackend.exit());
        assertTrue(badBackend.err().contains("unknown backend 'uppaal' (use engine or tron)"), badBackend.err());
    }

    @Test
    void anAdapterTimeUnitTooLongForTheDefaultTimeoutIsRefusedWithTheReason() throws Exception {
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            CompletableFuture<String> adapter = CompletableFuture.supplyAsync(() -> {
                try (var socket = server.accept(); RawClient c = RawClient.over(socket)) {
                    c.bytes(1).string("grasp");
                    assertEquals(1, c.readInt());
                    c.bytes(5).int32(Integer.MAX_VALUE).int32(0);
                    assertEquals(0, c.readInt(), "a time unit alone fits");
                    c.bytes(64);
                    return c.readString();
                } catch (IOException e) {
                    throw new IllegalStateException(e);
                }
            });
            CommandRun r = CommandRun.of("run", lightContr.toString(), "--tron-adapter", "127.0.0.1:" + server.getLocalPort());
            String reason = "the timeout of 1000 time units of 2147483647000000 us is longer than DTRON can time: at"
                    + " most 9223372036854775 us (about 292 years) (timeout from the default, time unit from the"
                    + " adapter)";
            assertEquals("DTRON refuses the start: " + reason, adapter.get(10, TimeUnit.SECONDS));
            assertEquals(1, r.exit(), r.out() + r.err());
            assertTrue(r.err().contains("dtron run: " + reason), r.err());
            assertFalse(r.err().contains("Exception") || r.err().contains("\tat "), "no stack trace: " + r.err());
        }
    }

    @Test
    void nobodyListeningAtTheTronAdapterAddressIsAClearError() throws Exception {
        int port;
        try (ServerSocket probe = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            port = probe.getLocalPort();
        }
        CommandRun r = CommandRun.of("run", lightContr.toString(), "--tron-adapter", "127.0.0.1:" + port);
        assertEquals(1, r.exit());
        assertTrue(r.err().contains("dtron run: the TRON adapter's configuration failed: cannot connect to the"
                + " adapter at 127.0.0.1:" + port), r.err());
        assertFalse(r.err().contains("\tat "), "no stack trace: " + r.err());
    }

    /** dtron run in a JVM of its own, with TRON_HOME and PATH as given. */
    private Process dtronProcess(String tronHome, String path, Path log, String... args) throws IOException {
        List<String> command = new ArrayList<>(ChildProcess.command(DtronCommand.class, args));
        ProcessBuilder builder = new ProcessBuilder(command).redirectErrorStream(true).redirectOutput(log.toFile());
        builder.environment().remove("TRON_HOME");
        if (tronHome != null) {
            builder.environment().put("TRON_HOME", tronHome);
        }
        builder.environment().put("PATH", path);
        return builder.start();
    }

    /** A TRON_HOME whose bin/tron runs DTRON in TRON's place. */
    private Path tronHome() throws IOException {
        Path bin = dir.resolve("tron-home").resolve("bin");
        Files.createDirectories(bin);
        Path script = bin.resolve("tron");
        String command = ChildProcess.command(FakeTronMain.class).stream().map(a -> "'" + a + "'")
                .collect(Collectors.joining(" "));
        Files.writeString(script, "#!/bin/sh\nexec " + command + " \"$@\"\n");
        Files.setPosixFilePermissions(script, PosixFilePermissions.fromString("rwxr-xr-x"));
        return dir.resolve("tron-home");
    }

    /**
     * Microseconds per time unit of the runs judged by the installed TRON: TRON's protocol carries no event times, so
     * an output counts when it reaches TRON, here through one process more than in the other tests of this class;
     * at 10 ms per unit a busy machine (two busy cores and the build) held an on-time level of the correct lamp back
     * past the model's 15-unit window (1 run in 12).
     */
    private static final int BACKEND_TIME_UNIT = 50_000;

    private String runWithTronBackend(String variant, int expectedExit) throws Exception {
        Path log = dir.resolve("dtron-" + variant + ".log");
        Process p = dtronProcess(tronHome().toString(), "/usr/bin:/bin", log, "run", lightContr.toString(),
                "--interface", tronModels.resolve("LightContr.trn").toString(), "--sut",
                LampSystem.class.getName() + ":" + variant, "--timeunit",
                Integer.toString(BACKEND_TIME_UNIT), "--timeout", "300", "--seed", "42",
                "--backend", "tron");
        assertTrue(p.waitFor(90, TimeUnit.SECONDS), Files.readString(log));
        String out = Files.readString(log);
        assertEquals(expectedExit, p.exitValue(), out);
        assertTrue(out.contains("seed 42, 300 time units of " + BACKEND_TIME_UNIT
                + " us, judged by Uppaal TRON"), out);
        return out;
    }

    @Test
    void theInstalledTronJudgesTheCorrectSystemPassed() throws Exception {
        String out = runWithTronBackend("correct", 0);
        assertTrue(out.contains("\nPASSED: the timeout of 300 time units was reached"), out);
        assertTrue(out.contains("statistics: 42 PASSED "), out);
        assertTrue(out.contains("tron: dtron tron: "), "TRON's own output is shown behind 'tron: ': " + out);
    }

    @Test
    void aTimeoutBeyondTronsIsAUsageError() throws Exception {
        Path log = dir.resolve("dtron-long.log");
        Process p = dtronProcess(tronHome().toString(), "/usr/bin:/bin", log, "run", lightContr.toString(),
                "--interface", tronModels.resolve("LightContr.trn").toString(), "--sut", LampSystem.class.getName(),
                "--timeout", "3000000000", "--backend", "tron");
        assertTrue(p.waitFor(90, TimeUnit.SECONDS), Files.readString(log));
        String out = Files.readString(log);
        assertEquals(1, p.exitValue(), out);
        assertTrue(out.contains("dtron run: --backend tron: TRON's timeout is at most 2147483647 time units\n"
                + "see 'dtron run --help'"), out);
        assertFalse(out.contains("Exception"), out);
    }

    @Test
    void theInstalledTronJudgesTheLateSystemFailed() throws Exception {
        String out = runWithTronBackend("late", 2);
        assertTrue(out.contains("\nFAILED: "), out);
    }

    @Test
    void theInstalledTronJudgesTheAdaptersOnTheBus() throws Exception {
        Path log = dir.resolve("bus.log");
        Path ticker = Path.of("..", "models", "src", "main", "resources", "io", "dtron", "models", "ticker.xml");
        // 200 ms per unit: TRON judges outputs when they reach it, through one more process; at 50 ms a busy
        // machine delayed an on-time tick past the model's 2 units there
        Process p = dtronProcess(tronHome().toString(), "/usr/bin:/bin", log, "run", ticker.toString(),
                "--adapter", BusTicker.class.getName(), "--cluster", "tron-" + UUID.randomUUID().toString()
                        .substring(0, 8), "--timeunit", "200000", "--timeout", "40", "--delay-policy", "eager",
                "--seed", "5", "--backend", "tron");
        assertTrue(p.waitFor(90, TimeUnit.SECONDS), Files.readString(log));
        String out = Files.readString(log);
        assertEquals(0, p.exitValue(), out);
        assertTrue(out.contains("seed 5, 40 time units of 200000 us in real time, judged by Uppaal TRON"), out);
        assertTrue(out.contains("\nPASSED: the timeout of 40 time units was reached"), out);
        assertTrue(out.contains("latency t2 - t1 of outputs: count "), out);
    }

    @Test
    void aTronThatFailsToStartIsAClearErrorWithWhatItPrinted() throws Exception {
        Path home = dir.resolve("broken-tron");
        Files.createDirectories(home.resolve("bin"));
        Path script = home.resolve("bin").resolve("tron");
        Files.writeString(script, "#!/bin/sh\necho 'tron: cannot parse the model' >&2\nexit 1\n");
        Files.setPosixFilePermissions(script, PosixFilePermissions.fromString("rwxr-xr-x"));
        Path log = dir.resolve("broken.log");
        Process p = dtronProcess(home.toString(), "/usr/bin:/bin", log, "run", lightContr.toString(), "--interface",
                tronModels.resolve("LightContr.trn").toString(), "--sut", LampSystem.class.getName(), "--backend",
                "tron");
        assertTrue(p.waitFor(60, TimeUnit.SECONDS));
        String out = Files.readString(log);
        assertEquals(1, p.exitValue(), out);
        assertTrue(out.contains("dtron run: --backend tron: TRON ended (exit code 1) without connecting to DTRON; it"
                + " printed: tron: cannot parse the model"), out);
        assertFalse(out.contains("\tat "), "no stack trace: " + out);
    }

    @Test
    void withoutTronTheBackendSaysWhereItLookedAndWhatToDo() throws Exception {
        Path log = dir.resolve("missing.log");
        Process p = dtronProcess(null, dir.resolve("empty").toString(), log, "run", lightContr.toString(),
                "--interface", tronModels.resolve("LightContr.trn").toString(), "--sut", LampSystem.class.getName(),
                "--backend", "tron");
        assertTrue(p.waitFor(60, TimeUnit.SECONDS));
        String out = Files.readString(log);
        assertEquals(1, p.exitValue(), out);
        assertTrue(out.contains("dtron run: --backend tron: Uppaal TRON was not found: no executable 'tron'"
                + " (TRON_HOME is not set, and not on PATH)"), out);
        assertTrue(out.contains("leave out --backend tron"), out);
        assertFalse(out.contains("\tat "), "no stack trace: " + out);
    }
}
