package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@link RealTimeJit} in JVMs of their own ({@link RealTimeJitProbe}): dtron's own JVM excludes every method from C2
 * when a real-time run asks, one started with a compilation option of its own is left as it is, and an embedding JVM
 * (not started by dtron's main) keeps its compilers.
 */
class RealTimeJitTest {
    /** A directive's C2 part that excludes what it matches, in HotSpot's print of the directives. */
    private static final Pattern C2_EXCLUDED = Pattern.compile(
            "c2 directives:\\s+inline: -\\s+Enable:true Exclude:true");

    @TempDir
    Path dir;

    private String probe(List<String> jvmOptions, String... args) throws Exception {
        List<String> command = new ArrayList<>(List.of(ChildProcess.tool("java")));
        command.addAll(jvmOptions);
        command.addAll(List.of("-cp", System.getProperty("java.class.path"), RealTimeJitProbe.class.getName()));
        command.addAll(List.of(args));
        return ChildProcess.run(dir, dir.resolve("probe.log"), Duration.ofMinutes(1), command);
    }

    private static int excluding(String printed) {
        Matcher m = C2_EXCLUDED.matcher(printed);
        int n = 0;
        while (m.find()) {
            n++;
        }
        return n;
    }

    @Test
    void dtronsOwnJvmCompilesWithC1Alone() throws Exception {
        String printed = probe(List.of(), "own");
        assertTrue(printed.contains("compiles quickly: true"), printed);
        assertEquals(1, excluding(printed), printed);
    }

    @Test
    void aJvmStartedWithItsOwnCompilationOptionKeepsThem() throws Exception {
        String printed = probe(List.of("-XX:TieredStopAtLevel=4"), "own");
        assertTrue(printed.contains("compiles quickly: false"), printed);
        assertEquals(0, excluding(printed), printed);
    }

    @Test
    void anEmbeddingJvmKeepsItsCompilers() throws Exception {
        String printed = probe(List.of());
        assertTrue(printed.contains("compiles quickly: false"), printed);
        assertEquals(0, excluding(printed), printed);
    }
}
