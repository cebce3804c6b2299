package io.dtron.engine.verify;

import java.time.Duration;
import java.util.Objects;

/**
 * How a {@link Verifier} searches.
 *
 * @param order            the search order of reachability queries
 * @param timeLimit        the longest time one query may take, or null for none
 * @param memoryLimitBytes the most heap memory a search may use, or 0 for no limit
 * @param progressInterval how often a long search logs its progress (slf4j, level INFO)
 */
public record VerifierOptions(SearchOrder order, Duration timeLimit, long memoryLimitBytes,
                              Duration progressInterval) {

    public VerifierOptions {
        Objects.requireNonNull(order, "order");
        Objects.requireNonNull(progressInterval, "progressInterval");
        if (memoryLimitBytes < 0) {
            throw new IllegalArgumentException("memory limit must not be negative");
        }
    }

    /** Breadth-first, no limits, progress every 5 seconds. */
    public static VerifierOptions defaults() {
        return new VerifierOptions(SearchOrder.BREADTH_FIRST, null, 0, Duration.ofSeconds(5));
    }

    /** These options with another search order. */
    public VerifierOptions withOrder(SearchOrder newOrder) {
        return new VerifierOptions(newOrder, timeLimit, memoryLimitBytes, progressInterval);
    }

    /** These options with another time limit (null for none). */
    public VerifierOptions withTimeLimit(Duration limit) {
        return new VerifierOptions(order, limit, memoryLimitBytes, progressInterval);
    }

    /** These options with another memory limit (0 for none). */
    public VerifierOptions withMemoryLimit(long bytes) {
        return new VerifierOptions(order, timeLimit, bytes, progressInterval);
    }
}
