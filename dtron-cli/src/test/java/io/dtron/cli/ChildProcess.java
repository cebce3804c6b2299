package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.fail;

import io.dtron.testsupport.PageProjects;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

/**
 * A command (java, javac, mvn) run by a test in a folder of its own, its standard output and error in one log, so
 * that a failing test can show what the command printed.
 */
final class ChildProcess implements AutoCloseable {
    /** Options that let a short-lived child JVM start fast on a busy machine. */
    static final List<String> FAST_JVM = List.of("-Xmx256m", "-XX:+UseSerialGC", "-XX:TieredStopAtLevel=1");

    private final List<String> command;
    private final Process process;
    private final Path log;

    private ChildProcess(List<String> command, Process process, Path log) {
        this.command = command;
        this.process = process;
        this.log = log;
    }

    /** Starts {@code command} in {@code dir}; its output goes to {@code log}. */
    static ChildProcess start(Path dir, Path log, List<String> command) throws IOException {
        ProcessBuilder builder = new ProcessBuilder(command)
                .directory(dir.toFile())
                .redirectErrorStream(true)
                .redirectOutput(log.toFile());
        if (command.get(0).equals(mvn())) {
            // a Maven of its own, not the build's project (its launcher exports these), quick to start unless the
            // build was given its own options
            builder.environment().remove("MAVEN_PROJECTBASEDIR");
            builder.environment().remove("MAVEN_CMD_LINE_ARGS");
            builder.environment().putIfAbsent("MAVEN_OPTS", "-XX:TieredStopAtLevel=1 -XX:+UseSerialGC");
        }
        return new ChildProcess(List.copyOf(command), builder.start(), log);
    }

    /** Starts {@code java} of this JVM's installation with {@link #FAST_JVM} and then {@code args}. */
    static ChildProcess java(Path dir, Path log, List<String> args) throws IOException {
        List<String> command = new ArrayList<>(List.of(tool("java")));
        command.addAll(FAST_JVM);
        command.addAll(args);
        return start(dir, log, command);
    }

    /** Runs {@code command} in {@code dir} to its end and fails the test, showing its output, unless it exits with 0. */
    static String run(Path dir, Path log, Duration timeout, List<String> command) throws Exception {
        try (ChildProcess child = start(dir, log, command)) {
            int exit = child.waitFor(timeout);
            if (exit != 0) {
                fail(child.describe() + " exited with " + exit + "; its output:\n" + child.output());
            }
            return child.output();
        }
    }

    /** The path of a JDK tool ({@code java}, {@code javac}) of the JDK running the tests. */
    static String tool(String name) {
        return Path.of(System.getProperty("java.home"), "bin", name).toString();
    }

    /** The {@code mvn} a user runs: see {@link PageProjects#mvn()}. */
    static String mvn() {
        return PageProjects.mvn();
    }

    /** Waits for the process to exit and returns its exit code; fails the test, showing its output, after the timeout. */
    int waitFor(Duration timeout) throws InterruptedException, IOException {
        if (!process.waitFor(timeout.toMillis(), TimeUnit.MILLISECONDS)) {
            kill();
            fail(describe() + " still running after " + timeout + "; its output:\n" + output());
        }
        return process.exitValue();
    }

    /** What the process printed so far. */
    String output() throws IOException {
        return Files.readString(log);
    }

    /** The command line, for messages. */
    String describe() {
        return "'" + String.join(" ", command) + "'";
    }

    private void kill() {
        process.descendants().forEach(ProcessHandle::destroyForcibly);
        process.destroyForcibly();
    }

    /** Kills the process (and what it started) if it still runs. */
    @Override
    public void close() {
        if (process.isAlive()) {
            kill();
        }
    }
}
