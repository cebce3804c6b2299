package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.fail;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.TimeUnit;

/** A page's shell commands run as the reader would run them: one {@code bash} script, in a folder of the test's choice. */
public final class ShellSession {
    private ShellSession() {
    }

    /**
     * Runs {@code lines} as one bash script in {@code folder}, its standard output and error in {@code log}, and
     * returns what it printed; fails the test, showing that, if it still runs after {@code timeout}. Whatever the
     * script left running is stopped when it ends.
     */
    public static String run(Path folder, List<String> lines, Path log, Duration timeout) throws Exception {
        Path script = Files.createTempFile(log.getParent(), "session", ".sh");
        Files.write(script, lines);
        Process bash = new ProcessBuilder("bash", script.toString()).directory(folder.toFile())
                .redirectErrorStream(true).redirectOutput(log.toFile()).start();
        try {
            if (!bash.waitFor(timeout.toMillis(), TimeUnit.MILLISECONDS)) {
                fail("the session " + lines + " still runs after " + timeout + "; it printed:\n"
                        + Files.readString(log));
            }
        } finally {
            bash.descendants().forEach(ProcessHandle::destroyForcibly);
            bash.destroyForcibly();
        }
        return Files.readString(log);
    }
}
