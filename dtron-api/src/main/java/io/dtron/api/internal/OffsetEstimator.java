package io.dtron.api.internal;

import java.util.ArrayDeque;
import java.util.Deque;
import java.util.Optional;

/**
 * Not API. Estimates (tester's clock - own clock) from ping round trips: each sample gives
 * {@code offset = ((tTester - t0) + (tTester - t3)) / 2} with {@code t0} the ping's send time and {@code t3} the
 * pong's receive time on the own clock, {@code tTester} the tester's clock when it received the ping; the true
 * offset lies within half the round trip {@code t3 - t0} of it. The estimate is the sample with the smallest round
 * trip among the last few. Not thread-safe.
 */
public final class OffsetEstimator {
    /** How many of the latest samples the estimate is chosen from. */
    public static final int WINDOW = 8;

    /**
     * An estimate: the offset and its error bound (at least 1 ns).
     *
     * @param offsetNanos tester's clock - own clock
     * @param errorNanos  half the round trip of the sample, rounded up; at least 1
     */
    public record Estimate(long offsetNanos, long errorNanos) {
    }

    private record Sample(long offsetNanos, long roundTripNanos) {
    }

    private final Deque<Sample> samples = new ArrayDeque<>();

    /**
     * Adds a sample; a negative round trip (the own clock stepped back) is ignored.
     *
     * @return the estimate now
     */
    public Optional<Estimate> add(long t0, long testerTime, long t3) {
        long roundTrip = t3 - t0;
        if (roundTrip >= 0) {
            // the halves are taken apart so that epoch-sized times cannot overflow
            long offset = Math.floorDiv(testerTime - t0, 2) + Math.floorDiv(testerTime - t3, 2)
                    + ((Math.floorMod(testerTime - t0, 2) + Math.floorMod(testerTime - t3, 2)) / 2);
            samples.addLast(new Sample(offset, roundTrip));
            if (samples.size() > WINDOW) {
                samples.removeFirst();
            }
        }
        return estimate();
    }

    /** Returns the estimate from the samples in the window, if any. */
    public Optional<Estimate> estimate() {
        Sample best = null;
        for (Sample sample : samples) {
            if (best == null || sample.roundTripNanos() < best.roundTripNanos()) {
                best = sample;
            }
        }
        return best == null
                ? Optional.empty()
                : Optional.of(new Estimate(best.offsetNanos(), Math.max(1, (best.roundTripNanos() + 1) / 2)));
    }

    /** Forgets all samples. */
    public void clear() {
        samples.clear();
    }
}
