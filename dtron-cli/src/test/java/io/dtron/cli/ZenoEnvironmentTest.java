package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * A model whose environment may give inputs with no time between them ({@code zeno-lamp.xta}): time still advances,
 * and a lamp that misses its deadline fails, naming it, in virtual and in real time.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class ZenoEnvironmentTest {
    @TempDir
    static Path dir;
    static Path model;
    static Path trn;

    @BeforeAll
    static void copyModel() throws IOException {
        model = copy("zeno-lamp.xta");
        trn = copy("zeno-lamp.trn");
    }

    private static Path copy(String name) throws IOException {
        Path to = dir.resolve(name);
        try (InputStream in = ZenoEnvironmentTest.class.getResourceAsStream(name)) {
            Files.copy(in, to);
        }
        return to;
    }

    /** The model time (units) at which a FAILED verdict was given, from the run's statistics line. */
    private static double verdictTime(CommandRun r, long unitMicros) {
        Matcher m = Pattern.compile("statistics: \\d+ FAILED \\d+ \\d+ (\\d+)").matcher(r.out());
        assertTrue(m.find(), r.out());
        return Long.parseLong(m.group(1)) / (double) unitMicros;
    }

    @Test
    void aSilentLampFailsAtItsDeadlineInVirtualTime() {
        for (String policy : new String[] {"random", "eager"}) {
            CommandRun r = CommandRun.of("run", model.toString(), "--interface", trn.toString(), "--sut",
                    ZenoLamp.class.getName() + ":silent", "--virtual-time", "--seed", "3", "--delay-policy", policy);
            assertEquals(2, r.exit(), policy + ": " + r.out() + r.err());
            Matcher m = Pattern.compile("FAILED: no output came by t=(\\d+\\.\\d+): the model required")
                    .matcher(r.out());
            assertTrue(m.find(), policy + ": " + r.out());
            double deadline = Double.parseDouble(m.group(1));
            assertTrue(r.out().contains("level between "), r.out());
            assertTrue(verdictTime(r, 10000) - deadline < 1, policy + ": " + r.out());
        }
    }

    @Test
    void aSilentLampFailsAtItsDeadlineInRealTimeAndTheRunSaysTheEnvironmentIsZeno() {
        CommandRun r = CommandRun.of("run", model.toString(), "--interface", trn.toString(), "--sut",
                ZenoLamp.class.getName() + ":silent", "--seed", "3", "--timeout", "100");
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("dtron run: the environment may give inputs with no time passing (Zeno): the"
                + " cycle Ready -> Ready of User may take no time; the tester gives at most 100 inputs at one"
                + " instant"), r.out());
        Matcher m = Pattern.compile("FAILED: no output came by t=(\\d+\\.\\d+): the model required").matcher(r.out());
        assertTrue(m.find(), r.out());
        assertTrue(r.out().contains("level between "), r.out());
        // within a second of the deadline (100 units of 10 ms), by the verdict's own time
        assertTrue(verdictTime(r, 10000) - Double.parseDouble(m.group(1)) < 100, r.out());
    }

    @Test
    void anEnvironmentThatAllowsNoTimeToPassIsInconclusiveNotFailed() throws IOException {
        // the user must act by t=3 and its inputs do not let time pass: the tester cannot give inputs without end,
        // and the system under test is not at fault
        Path stuck = dir.resolve("stuck-user.xta");
        Files.writeString(stuck, Files.readString(model).replace("process User() {\n    state Ready;",
                "process User() {\n    clock z;\n    state Ready { z <= 3 };"));
        CommandRun r = CommandRun.of("run", stuck.toString(), "--interface", trn.toString(), "--sut",
                ZenoLamp.class.getName() + ":silent", "--virtual-time", "--seed", "3", "--delay-policy", "eager");
        assertEquals(3, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("INCONCLUSIVE: no input was applied by t=3.000: the environment allowed inputs"
                + " until then but no time to pass without one, and the tester let time pass after 100 inputs at"
                + " t=3.000"), r.out());
    }

    @Test
    void theCorrectLampPassesInRealTimeWithShortAndLongDelayBounds() {
        CommandRun r = CommandRun.of("run", model.toString(), "--interface", trn.toString(), "--sut",
                ZenoLamp.class.getName(), "--seed", "3", "--timeout", "100", "--delay-policy", "random-bounded",
                "--delay-bound", "1,5");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("PASSED: the timeout of 100 time units was reached"), r.out());
    }
}
