package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.ShellSession;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron.jar} in a heap too small for DTRON itself ({@code -Xmx4m}: no room even for the line a full heap
 * prints; {@code -Xmx6m}: room for the line, not for the command) ends with one line naming the heap limit and the
 * {@code -Xmx} to use, and exit code 1: no stack trace, no line of the JVM's own.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class HeapLimitTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();

    @TempDir
    Path dir;

    @Test
    void aHeapTooSmallForDtronIsOneLineWithTheLimitAndTheXmxToUse() throws Exception {
        assertTrue(Files.isRegularFile(ROOT.resolve("dtron-cli/target/dtron.jar")),
                "the test runs dtron-cli/target/dtron.jar: build it first (mvn install)");
        List<String> heaps = List.of("4", "6");
        List<String> script = new ArrayList<>();
        for (String heap : heaps) {
            script.add("echo heap " + heap);
            script.add("java -Xmx" + heap + "m -jar dtron-cli/target/dtron.jar check"
                    + " models/src/main/resources/io/dtron/models/ticker.xml");
            script.add("echo exit $?");
        }
        String output = ShellSession.run(ROOT, script, dir.resolve("heap.log"), Duration.ofSeconds(100));
        List<String> lines = output.lines().toList();
        assertEquals(3 * heaps.size(), lines.size(), "one line per command: " + output);
        for (int i = 0; i < heaps.size(); i++) {
            String heap = heaps.get(i);
            assertEquals("heap " + heap, lines.get(3 * i), output);
            // where the heap runs out depends on the JVM's collections: before the command runs (the general line)
            // or while it loads the model (the command's line, naming the file)
            assertTrue(lines.get(3 * i + 1).matches("dtron( check: \\S+)?: out of memory: .*Java heap limit of "
                    + heap + " MB.*; raise .*, e\\.g\\. java -Xmx\\d+m -jar dtron\\.jar .+"), output);
            assertEquals("exit 1", lines.get(3 * i + 2), output);
        }
    }
}
