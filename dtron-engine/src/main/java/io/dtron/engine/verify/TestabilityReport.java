package io.dtron.engine.verify;

import java.util.List;

/**
 * What {@link Verifier#testability} found: one entry per check, in a fixed order, each passed or with its
 * problems.
 *
 * @param checks     the checks
 * @param statistics the figures of the exploration they share
 */
public record TestabilityReport(List<Check> checks, VerificationResult.Statistics statistics) {

    public TestabilityReport {
        checks = List.copyOf(checks);
    }

    /**
     * One check.
     *
     * @param name     what it checks ({@code "input enabledness"})
     * @param problems what fails it, each with a trace to where (empty: the check passes)
     * @param note     what the check assumes or leaves out, or null
     */
    public record Check(String name, List<Problem> problems, String note) {
        public Check {
            problems = List.copyOf(problems);
        }

        /** Whether the check found nothing. */
        public boolean passed() {
            return problems.isEmpty();
        }
    }

    /**
     * A problem found by a check.
     *
     * @param message what is wrong, naming processes, locations, channels
     * @param trace   a path to a state where it shows, or null for a problem of the model's structure
     */
    public record Problem(String message, Trace trace) {
    }

    /** Whether every check passed. */
    public boolean passed() {
        return checks.stream().allMatch(Check::passed);
    }
}
