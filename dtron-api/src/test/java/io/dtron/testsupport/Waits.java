package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.fail;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.regex.MatchResult;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.awaitility.Awaitility;
import org.awaitility.core.ConditionFactory;
import org.awaitility.core.ConditionTimeoutException;

/**
 * The one way the tests wait for what another thread or process does: Awaitility, polling every 10 ms, with a
 * timeout generous for a loaded machine. A wait ends as soon as its condition holds, so the long timeout costs
 * nothing when all is well; it only decides how long a test that is going to fail hangs.
 */
public final class Waits {
    /** How long a wait lasts at most: long enough for a machine whose cores are all busy. */
    public static final Duration TIMEOUT = Duration.ofSeconds(60);
    private static final Duration POLL = Duration.ofMillis(10);

    private Waits() {
    }

    /**
     * Awaitility's {@code await}, named {@code what} (a timeout names it), with the tests' timeout and poll. It
     * leaves other threads' uncaught exceptions alone (Awaitility would fail the wait on them): some tests make
     * threads fail on purpose.
     */
    public static ConditionFactory await(String what) {
        return Awaitility.await(what).atMost(TIMEOUT).pollDelay(Duration.ZERO).pollInterval(POLL)
                .dontCatchUncaughtExceptions();
    }

    /**
     * Waits until {@code output}, the file a child process writes its output to, matches {@code pattern}, and
     * returns the first match; fails the test, showing the output, if the process exits first or the timeout
     * passes.
     */
    public static MatchResult awaitOutput(Process process, Path output, Pattern pattern, Duration timeout) {
        String what = process.info().command().orElse("process " + process.pid()) + " printing '" + pattern + "'";
        try {
            // an exit ends the wait too: the output is complete then, and tells why
            await(what).atMost(timeout).until(() -> !process.isAlive() || pattern.matcher(read(output)).find());
        } catch (ConditionTimeoutException e) {
            fail("no '" + pattern + "' within " + timeout + " in the output:\n" + read(output));
        }
        Matcher matcher = pattern.matcher(read(output));
        if (!matcher.find()) {
            fail("exited with " + process.exitValue() + " before printing '" + pattern + "'; its output:\n"
                    + read(output));
        }
        return matcher.toMatchResult();
    }

    private static String read(Path file) {
        try {
            return Files.exists(file) ? Files.readString(file) : "";
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }
}
