package io.dtron.engine.verify;

import java.time.Duration;
import java.util.Objects;

/**
 * The answer to one query.
 *
 * @param query      the query
 * @param outcome    whether it holds, does not, could not be decided, or was skipped
 * @param reason     why the outcome is {@link Outcome#UNKNOWN} or {@link Outcome#SKIPPED}, else null
 * @param statistics the search's figures
 * @param trace      a diagnostic trace (a witness of a satisfied {@code E<>} or {@code E[]}, a counterexample
 *                   of a violated {@code A[]}, {@code A<>} or {@code -->}), or null
 */
public record VerificationResult(Query query, Outcome outcome, String reason, Statistics statistics, Trace trace) {

    /** What the checker found. */
    public enum Outcome {
        /** The query holds. */
        SATISFIED,
        /** The query does not hold. */
        VIOLATED,
        /** The search stopped at a limit before it could decide. */
        UNKNOWN,
        /** The query is of a kind the checker does not check. */
        SKIPPED
    }

    /**
     * The figures of one search.
     *
     * @param explored    symbolic states whose successors were computed
     * @param stored      symbolic states kept in the passed list at the end
     * @param time        wall time of the search
     * @param memoryBytes the most heap in use seen during the search (sampled)
     */
    public record Statistics(long explored, long stored, Duration time, long memoryBytes) {
        /** No search. */
        public static final Statistics NONE = new Statistics(0, 0, Duration.ZERO, 0);
    }

    public VerificationResult {
        Objects.requireNonNull(query, "query");
        Objects.requireNonNull(outcome, "outcome");
        Objects.requireNonNull(statistics, "statistics");
    }
}
