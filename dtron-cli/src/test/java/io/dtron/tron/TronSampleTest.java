package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.cli.CommandRun;
import io.dtron.testsupport.DocPage;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.regex.Pattern;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * TRON's smart-lamp sample as TRON runs it, against {@code dtron tron}: an adapter written against TRON's Java API
 * shape ({@link TronSampleLamp} on the {@code com.uppaal.tron} fixture) in a JVM of its own, over TCP on loopback,
 * with TRON's command lines: {@code -qQ PORT} serves the virtual clock and the lamp is started with {@code -C
 * localhost PORT}; in real time without them. The correct lamp passes, the late one fails.
 */
@Timeout(value = 180, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronSampleTest {
    private static Path lightContr;

    @TempDir
    Path dir;

    @BeforeAll
    static void find() throws Exception {
        lightContr = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron", "LightContr.xml");
        Warmup.lightContr(io.dtron.model.ModelLoader.load(lightContr));
    }

    static int freePort() throws Exception {
        try (ServerSocket probe = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            return probe.getLocalPort();
        }
    }

    /** A finished sample run: dtron tron's output, the lamp's, and how long dtron tron took. */
    record Sample(CommandRun tron, String lamp, int lampExit, Duration took) {
    }

    /**
     * Runs {@code dtron tron OPTIONS LightContr.xml -- localhost LAMP} and the lamp (with {@code -C localhost CLOCK}
     * when {@code clock} is positive), dtron tron started first, as TRON's Makefile starts both.
     */
    private Sample run(int clock, String variant, int timeout, int unit, String... options) throws Exception {
        int lampPort = freePort();
        List<String> args = new ArrayList<>(List.of("tron"));
        args.addAll(List.of(options));
        args.addAll(List.of(lightContr.toString(), "--", "localhost", Integer.toString(lampPort)));
        List<String> lampArgs = new ArrayList<>();
        if (clock > 0) {
            lampArgs.addAll(List.of("-C", "localhost", Integer.toString(clock)));
        }
        lampArgs.addAll(List.of(Integer.toString(lampPort), variant, Integer.toString(timeout),
                Integer.toString(unit)));
        long start = System.nanoTime();
        // in virtual time dtron tron comes first (the lamp's threads connect to its clock, then the lamp listens);
        // in real time the lamp listens first, as TRON's sample has it
        CompletableFuture<CommandRun> tron = clock > 0 ? CompletableFuture.supplyAsync(() -> CommandRun.of(
                args.toArray(String[]::new))) : null;
        try (ChildJvm lamp = ChildJvm.start(TronSampleLamp.class, dir.resolve("lamp-" + variant + ".log"),
                lampArgs.toArray(String[]::new))) {
            if (tron == null) {
                lamp.awaitOutput("PORT ", Duration.ofSeconds(30));
                tron = CompletableFuture.supplyAsync(() -> CommandRun.of(args.toArray(String[]::new)));
            }
            CommandRun r = tron.get(150, TimeUnit.SECONDS);
            Duration took = Duration.ofNanos(System.nanoTime() - start);
            int exit = lamp.waitFor(Duration.ofSeconds(30));
            return new Sample(r, lamp.output(), exit, took);
        }
    }

    @Test
    void theCorrectLampPassesInVirtualTimeWithTronsClockServerFasterThanItsTestTime() throws Exception {
        int clock = freePort();
        Path stats = dir.resolve("stats");
        Sample s = run(clock, "correct", 60_000, 1000, "-qQ", Integer.toString(clock), "-I", "SocketAdapter", "-P",
                "10,200", "-X", "7", "-S", stats.toString());
        assertEquals(0, s.tron().exit(), s.tron().out() + s.tron().err() + s.lamp());
        assertTrue(s.tron().out().startsWith("TEST PASSED: the timeout of 60000 time units was reached"),
                s.tron().out());
        assertEquals(1, s.tron().out().lines().count(), "-q prints the verdict only: " + s.tron().out());
        assertEquals(0, s.lampExit(), s.lamp());
        assertTrue(s.lamp().contains("END"), s.lamp());
        String[] line = Files.readString(stats).strip().split(" ");
        assertTrue(Integer.parseInt(line[2]) > 100 && Integer.parseInt(line[3]) > 100, Files.readString(stats));
        assertEquals("60000000", line[4], "the duration is virtual: " + Files.readString(stats));
        // 60 s of test time; the run, the lamp JVM's start included, takes less (a few seconds when all is well)
        assertTrue(s.took().toSeconds() < 60, "took " + s.took());
        // virtual time is deterministic: the same seed, the same run
        Path again = dir.resolve("again");
        int clock2 = freePort();
        Sample second = run(clock2, "correct", 60_000, 1000, "-qQ", Integer.toString(clock2), "-I", "SocketAdapter",
                "-P", "10,200", "-X", "7", "-S", again.toString());
        assertEquals(0, second.tron().exit(), second.tron().out() + second.tron().err() + second.lamp());
        assertEquals(Files.readString(stats), Files.readString(again));
    }

    @Test
    void theLateLampFailsInVirtualTime() throws Exception {
        int clock = freePort();
        Sample s = run(clock, "late", 5000, 1000, "-Q", Integer.toString(clock), "-X", "8", "-v", "1");
        assertEquals(2, s.tron().exit(), s.tron().out() + s.tron().err() + s.lamp());
        assertTrue(s.tron().out().contains("dtron tron: virtual clock server on 127.0.0.1:" + clock), s.tron().out());
        assertTrue(s.tron().out().contains("TEST FAILED: "), s.tron().out());
        assertTrue(s.tron().out().contains("levelAdapter"), s.tron().out());
        assertEquals(0, s.lampExit(), s.lamp());
    }

    @Test
    void theCorrectLampPassesAndTheLateOneFailsInRealTime() throws Exception {
        Sample correct = run(0, "correct", 300, TronLampEndToEndTest.REAL_TIME_UNIT, "-I", "SocketAdapter", "-P",
                "10,200", "-F", "300", "-X", "9", "-q");
        assertEquals(0, correct.tron().exit(), correct.tron().out() + correct.tron().err() + correct.lamp());
        assertTrue(correct.tron().out().startsWith("TEST PASSED"), correct.tron().out());
        assertEquals(0, correct.lampExit(), correct.lamp());
        Sample late = run(0, "late", 300, TronLampEndToEndTest.REAL_TIME_UNIT, "-I", "SocketAdapter", "-P", "10,200",
                "-F", "300", "-X", "9", "-q");
        assertEquals(2, late.tron().exit(), late.tron().out() + late.tron().err() + late.lamp());
        assertTrue(late.tron().out().startsWith("TEST FAILED: "), late.tron().out());
        assertTrue(late.tron().out().contains("levelAdapter"), late.tron().out());
    }

    /**
     * tron.md's command lines for TRON's sample as the page writes them, but for the ports (free ones instead of the
     * page's 9999 and 6521, which something else on this host may hold): the real-time line, and the virtual-time one
     * with the lamp started on the clock server; the correct lamp passes both, with the page's verdict line.
     */
    @Test
    void tronPagesCommandLinesPassTheCorrectLamp() throws Exception {
        DocPage page = DocPage.read("tron.md");
        List<String> realTime = List.of(page.blockAfter("TRON's smart-lamp sample, where the").code().lines().toList()
                .get(1).split("\\s+"));
        List<String> virtual = new ArrayList<>(List.of(page.blockAfter("The same command lines run DTRON:").code()
                .lines().toList().get(0).split("\\s+")));
        String lamp = page.blockAfter("The same command lines run DTRON:").code().lines().toList().get(1);
        assertEquals("&", virtual.remove(virtual.size() - 1), "the page starts dtron tron in the background");
        assertTrue(lamp.endsWith(" -C localhost 6521"), lamp);
        String shown = page.blockAfter("the verdict as").code().strip();
        String verdict = shown.substring(0, shown.indexOf(" after ") + 7);
        for (List<String> line : List.of(realTime, virtual)) {
            int model = line.indexOf("LightContr.xml");
            assertEquals(List.of("dtron", "tron"), line.subList(0, 2), line.toString());
            assertEquals(List.of("--", "localhost", "9999"), line.subList(model + 1, line.size()), line.toString());
            List<String> options = new ArrayList<>(line.subList(2, model));
            int clock = options.contains("-qQ") ? freePort() : 0;
            if (clock > 0) {
                assertEquals("6521", options.set(options.indexOf("-qQ") + 1, Integer.toString(clock)));
            }
            // the lamp's own time unit: 1 ms in virtual time, as the page says; 10 ms in real time, where a busy
            // machine holds threads up for milliseconds
            Sample s = run(clock, "correct", 1000, clock > 0 ? 1000 : TronLampEndToEndTest.REAL_TIME_UNIT,
                    options.toArray(String[]::new));
            String out = s.tron().out() + s.tron().err() + s.lamp();
            assertEquals(0, s.tron().exit(), out);
            String units = options.get(options.indexOf("-F") + 1);
            assertTrue(s.tron().out().lines().anyMatch(l -> l.matches(Pattern.quote(verdict.replace("300", units))
                    + "\\d+ inputs and \\d+ outputs, all as the model allows")), verdict + " in " + out);
            assertEquals(0, s.lampExit(), s.lamp());
        }
    }
}
