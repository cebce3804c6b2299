package io.dtron.api;

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

/** A main class of the tests, or a jar, run in a JVM of its own. */
public final class ChildJvm implements AutoCloseable {
    private final Process process;
    private final Path log;

    private ChildJvm(Process process, Path log) {
        this.process = process;
        this.log = log;
    }

    /** Starts {@code main} on the test classpath with the arguments; its stdout and stderr go to {@code log}. */
    public static ChildJvm start(Class<?> main, Path log, String... args) throws IOException {
        return start(List.of("-cp", System.getProperty("java.class.path"), main.getName()), log, args);
    }

    /**
     * Starts {@code main} on the test classpath with JVM options of its own (after the defaults, so that e.g. an
     * {@code -Xmx} of theirs wins) and the arguments; its stdout and stderr go to {@code log}.
     */
    public static ChildJvm start(List<String> jvmOptions, Class<?> main, Path log, String... args) throws IOException {
        List<String> what = new ArrayList<>(jvmOptions);
        what.addAll(List.of("-cp", System.getProperty("java.class.path"), main.getName()));
        return start(what, log, args);
    }

    /** Starts {@code java -jar jar} with the arguments; its stdout and stderr go to {@code log}. */
    public static ChildJvm startJar(Path jar, Path log, String... args) throws IOException {
        return start(List.of("-jar", jar.toString()), log, args);
    }

    private static ChildJvm start(List<String> what, Path log, String... args) throws IOException {
        List<String> command = new ArrayList<>(List.of(
                Path.of(System.getProperty("java.home"), "bin", "java").toString(),
                "-Xmx256m", "-XX:+UseSerialGC", "-XX:TieredStopAtLevel=1"));
        command.addAll(what);
        command.addAll(List.of(args));
        Process process = new ProcessBuilder(command)
                .redirectErrorStream(true)
                .redirectOutput(log.toFile())
                .start();
        return new ChildJvm(process, log);
    }

    /** Waits for the JVM to exit and returns its exit code; fails the test after the timeout. */
    public int waitFor(Duration timeout) throws InterruptedException, IOException {
        if (!process.waitFor(timeout.toMillis(), TimeUnit.MILLISECONDS)) {
            process.destroyForcibly();
            fail("child JVM still running after " + timeout + "; its output:\n" + output());
        }
        return process.exitValue();
    }

    /**
     * Waits until the JVM has printed {@code text}; fails the test if it exits first or the timeout passes.
     */
    public void awaitOutput(String text, Duration timeout) {
        Waits.awaitOutput(process, log, Pattern.compile(Pattern.quote(text)), timeout);
    }

    /** Kills the JVM at once, as a crash would. */
    public void kill() {
        process.destroyForcibly();
    }

    /** Stops the JVM (SIGSTOP), as a debugger or an overloaded host would: it neither runs nor leaves the bus. */
    public void suspend() throws IOException, InterruptedException {
        signal("-STOP");
    }

    /** Lets a {@linkplain #suspend suspended} JVM run again (SIGCONT). */
    public void resume() throws IOException, InterruptedException {
        signal("-CONT");
    }

    /**
     * Sends the JVM a signal, as {@code kill} names it: {@code -TERM} as a service manager stops a process, {@code
     * -INT} as Ctrl-C does.
     */
    public void signal(String signal) throws IOException, InterruptedException {
        int code = new ProcessBuilder("kill", signal, Long.toString(process.pid())).inheritIO().start().waitFor();
        if (code != 0) {
            fail("kill " + signal + " " + process.pid() + " exited with " + code);
        }
    }

    /** Returns the JVM's process, to watch it (its sockets, whether it still runs). */
    public ProcessHandle toHandle() {
        return process.toHandle();
    }

    /** Returns what the JVM printed so far. */
    public String output() throws IOException {
        return Files.readString(log);
    }

    /** Kills the JVM if it still runs, and waits (a few seconds at most) until it is gone. */
    @Override
    public void close() {
        if (process.isAlive()) {
            process.destroyForcibly();
        }
        try {
            // its ports are free once it is gone: a next test may bind them
            process.waitFor(10, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
