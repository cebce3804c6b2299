package io.dtron.engine.internal.verify;

import java.time.Duration;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The counters and limits of one search: states explored and stored, wall time, the most heap seen in use;
 * every 1024 explored states it checks the time and memory limits and, every progress interval, logs the
 * search's progress.
 */
final class Budget {
    private static final Logger LOG = LoggerFactory.getLogger("io.dtron.engine.verify");

    /** Thrown when a limit is reached; the search's answer is then unknown. */
    static final class LimitReached extends RuntimeException {
        private static final long serialVersionUID = 1L;

        LimitReached(String message) {
            super(message, null, false, false);
        }
    }

    private final String query;
    private final long start = System.nanoTime();
    private final long deadline;
    private final long memoryLimit;
    private final long progressNanos;
    private long nextProgress;
    long explored;
    long stored;
    private long peakMemory;

    Budget(String query, Duration timeLimit, long memoryLimit, Duration progressInterval) {
        this.query = query;
        this.deadline = timeLimit == null ? Long.MAX_VALUE : start + timeLimit.toNanos();
        this.memoryLimit = memoryLimit;
        this.progressNanos = progressInterval.toNanos();
        this.nextProgress = start + progressNanos;
        sampleMemory();
    }

    /** Counts one explored state; checks the limits now and then. */
    void explore() {
        explored++;
        if ((explored & 1023) == 0) {
            check();
        }
    }

    private void check() {
        long now = System.nanoTime();
        long used = sampleMemory();
        if (now > deadline) {
            throw new LimitReached("the time limit was reached after " + explored + " explored states");
        }
        if (memoryLimit > 0 && used > memoryLimit) {
            System.gc();
            if (sampleMemoryAfterGc() > memoryLimit) {
                throw new LimitReached("the memory limit was reached after " + explored + " explored states ("
                        + (used >> 20) + " MB in use)");
            }
        }
        if (now >= nextProgress) {
            nextProgress = now + progressNanos;
            LOG.info("{}: {} states explored, {} stored, {} s, {} MB", query, explored, stored,
                    (now - start) / 1_000_000_000L, used >> 20);
        }
    }

    private long sampleMemory() {
        Runtime rt = Runtime.getRuntime();
        long used = rt.totalMemory() - rt.freeMemory();
        peakMemory = Math.max(peakMemory, used);
        return used;
    }

    private long sampleMemoryAfterGc() {
        Runtime rt = Runtime.getRuntime();
        return rt.totalMemory() - rt.freeMemory();
    }

    Duration elapsed() {
        return Duration.ofNanos(System.nanoTime() - start);
    }

    long peakMemory() {
        sampleMemory();
        return peakMemory;
    }
}
