package io.dtron.models.lamp;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Path;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --replay} on runs of Uppaal TRON's smart lamp and its faulty variants against LightContr, in
 * virtual time: no violation in a correct lamp's runs, and each faulty lamp's violation at the time the tester
 * failed it (the early or wrong output's time, the missed deadline's).
 */
class LampMonitorTest {
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
    private static final String MODEL = SHARED.resolve("tron/LightContr.xml").toString();
    private static final String TRN = SHARED.resolve("tron/LightContr.trn").toString();
    private static final Pattern FAILED_AT = Pattern.compile("(?m)^FAILED: [^\\n]*?t=(\\d+\\.\\d{3})");

    private static String[] run(Path dir, String variant, long seed) {
        String trace = dir.resolve(variant + "-" + seed + ".jsonl").toString();
        StringWriter out = new StringWriter();
        int exit = DtronCommand.run(new String[] {"run", MODEL, "--interface", TRN, "--sut", SmartLamp.class.getName()
                + ":" + variant, "--virtual-time", "--seed", String.valueOf(seed), "--timeout", "3000", "--trace", trace},
                new PrintWriter(out), new PrintWriter(new StringWriter()));
        return new String[] {String.valueOf(exit), out.toString(), trace};
    }

    private static String[] monitor(String trace) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int exit = DtronCommand.run(new String[] {"monitor", MODEL, "--interface", TRN, "--replay", trace},
                new PrintWriter(out), new PrintWriter(err));
        assertEquals("", err.toString());
        return new String[] {String.valueOf(exit), out.toString()};
    }

    @Test
    void theMonitorFindsEachFaultyLampWhereTheTesterFailedIt(@TempDir Path dir) {
        for (String variant : SmartLamp.VARIANTS) {
            for (long seed = 1; seed <= 3; seed++) {
                String[] tester = run(dir, variant, seed);
                String[] monitor = monitor(tester[2]);
                String what = variant + " seed " + seed + ":\n" + tester[1] + monitor[1];
                if (variant.equals("correct")) {
                    assertEquals("0", tester[0], what);
                    assertEquals("0", monitor[0], what);
                    assertTrue(monitor[1].contains("no violation"), what);
                    continue;
                }
                assertEquals("2", tester[0], what);
                assertEquals("2", monitor[0], what);
                Matcher failed = FAILED_AT.matcher(tester[1]);
                assertTrue(failed.find(), what);
                assertTrue(monitor[1].contains("violation 1 at t=" + failed.group(1) + ": "), what);
            }
        }
    }
}
