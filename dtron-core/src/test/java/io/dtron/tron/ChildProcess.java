package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.fail;

import io.dtron.testsupport.Waits;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Pattern;

/** A main class of the tests run in a JVM of its own, on the test classpath, with its output in a file. */
final class ChildProcess implements AutoCloseable {
    private static final Pattern PORT = Pattern.compile("PORT (\\d+)");

    private final Process process;
    private final Path log;

    private ChildProcess(Process process, Path log) {
        this.process = process;
        this.log = log;
    }

    /** The command that runs {@code main} with the test classpath. */
    static List<String> command(Class<?> main, String... args) {
        List<String> command = new ArrayList<>(List.of(
                Path.of(System.getProperty("java.home"), "bin", "java").toString(),
                "-Xmx256m", "-XX:+UseSerialGC", "-XX:TieredStopAtLevel=1",
                "-cp", System.getProperty("java.class.path"),
                main.getName()));
        command.addAll(List.of(args));
        return command;
    }

    /** Starts {@code main} with the arguments; its stdout and stderr go to {@code log}. */
    static ChildProcess start(Class<?> main, Path log, String... args) throws IOException {
        Process process = new ProcessBuilder(command(main, args))
                .redirectErrorStream(true)
                .redirectOutput(log.toFile())
                .start();
        return new ChildProcess(process, log);
    }

    /** Waits for the child to print {@code PORT n} and returns n. */
    int awaitPort(Duration timeout) {
        return Integer.parseInt(Waits.awaitOutput(process, log, PORT, timeout).group(1));
    }

    /** Waits for the child to exit and returns its exit code; fails the test after the timeout. */
    int waitFor(Duration timeout) throws InterruptedException, IOException {
        if (!process.waitFor(timeout.toMillis(), TimeUnit.MILLISECONDS)) {
            process.destroyForcibly();
            fail("child JVM still running after " + timeout + "; its output:\n" + output());
        }
        return process.exitValue();
    }

    /** What the child printed so far. */
    String output() throws IOException {
        return Files.readString(log);
    }

    @Override
    public void close() {
        if (process.isAlive()) {
            process.destroyForcibly();
        }
    }
}
