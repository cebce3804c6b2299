package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code java -jar dtron.jar verify --trace json} in a process of its own: its standard output, as a pipe into
 * {@code jq} gets it, is JSON alone (nothing the JVM, the logging or the listing prints lands there), and its
 * standard error holds the text. Runs after the jar is built ({@code mvn verify}).
 */
class VerifyJsonJarIT {
    private static final Path JAR = Path.of("target", "dtron.jar");

    @Test
    void standardOutputOfTheJarIsJsonAlone(@TempDir Path dir) throws Exception {
        Path model = dir.resolve("crossing.xta");
        Files.writeString(model, DocPage.read("verify.md").blockAfter("On `crossing.xta`, a train and a gate").code());
        Path out = dir.resolve("out");
        Path err = dir.resolve("err");
        List<String> command = new ArrayList<>(List.of(ChildProcess.tool("java")));
        command.addAll(ChildProcess.FAST_JVM);
        command.addAll(List.of("-jar", JAR.toString(), "verify", model.toString(), "--query", "E<> Train.Cross",
                "--query", "A[] Gate.Open", "--query", "E<> Trian.Cross", "--trace", "json"));
        Process p = new ProcessBuilder(command).redirectOutput(out.toFile()).redirectError(err.toFile()).start();
        assertTrue(p.waitFor(120, TimeUnit.SECONDS), "dtron verify ends");
        String stderr = Files.readString(err);
        assertEquals(2, p.exitValue(), "a query does not hold: " + stderr);
        List<String> lines = Files.readAllLines(out);
        assertEquals(2, lines.size(), "two traces: " + lines);
        for (String line : lines) {
            Map<?, ?> trace = (Map<?, ?>) Json.parse(line);
            assertTrue(trace.containsKey("states"), line);
        }
        assertTrue(stderr.contains("[1] E<> Train.Cross\n    satisfied ("), stderr);
        assertTrue(stderr.contains("    counterexample: on standard output, JSON\n"), stderr);
        assertTrue(stderr.contains("    error: query 'E<> Trian.Cross', column 5: unknown process 'Trian' (did you mean"
                + " 'Train'?)\n"), stderr);
        assertTrue(stderr.contains("1 of 2 checked hold, 1 do not; 1 in error"), stderr);
    }
}
