package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.regex.Matcher;
import java.util.regex.Pattern;

/** What the summary line of {@code dtron run} ({@code bus: published N, accepted N, rejected N ...}) says. */
public final class BusSummary {
    private static final Pattern NOTHING_OF_THE_RUN = Pattern.compile(
            "(?m)^bus: published \\d+, accepted \\d+, rejected (0|(\\d+) \\(unauthenticated \\2\\)), ");

    private BusSummary() {
    }

    /**
     * Asserts that the run's tester rejected no message of the run's members. Frames without the bus's code may be
     * counted (as unauthenticated): other processes on the same bus ports with key files of their own (other
     * modules' and builds' tests, each with its own {@code DTRON_HOME}) reach the tester when they probe the ports,
     * and are dropped, as they should be. Returns how many were.
     */
    public static long assertNothingOfTheRunRejected(String out) {
        Matcher summary = NOTHING_OF_THE_RUN.matcher(out);
        assertTrue(summary.find(), "no message of the run was rejected: " + out);
        return summary.group(2) == null ? 0 : Long.parseLong(summary.group(2));
    }
}
