package io.dtron.api.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.api.internal.OffsetEstimator.Estimate;
import java.util.Optional;
import org.junit.jupiter.api.Test;

class OffsetEstimatorTest {
    private static final long EPOCH = 1_764_000_000_000_000_000L;

    @Test
    void theSampleWithTheShortestRoundTripOfTheWindowIsTheEstimate() {
        OffsetEstimator estimator = new OffsetEstimator();
        assertEquals(Optional.empty(), estimator.estimate());
        // tester 50 ms behind: it received at own time t0 + 1 ms - 50 ms; pong back 3 ms later (round trip 4 ms)
        long t0 = EPOCH;
        assertEquals(Optional.of(new Estimate(-50_000_000 - 1_000_000, 2_000_000)),
                estimator.add(t0, t0 + 1_000_000 - 50_000_000, t0 + 4_000_000));
        // a symmetric 1 ms round trip is better and exact
        assertEquals(Optional.of(new Estimate(-50_000_000, 500_000)),
                estimator.add(t0, t0 + 500_000 - 50_000_000, t0 + 1_000_000));
        // a worse sample does not replace it
        assertEquals(Optional.of(new Estimate(-50_000_000, 500_000)),
                estimator.add(t0, t0 + 9_000_000 - 50_000_000, t0 + 10_000_000));
        // a negative round trip (the clock stepped back) is no sample
        assertEquals(Optional.of(new Estimate(-50_000_000, 500_000)), estimator.add(t0, t0, t0 - 1));
    }

    @Test
    void oldSamplesLeaveTheWindow() {
        OffsetEstimator estimator = new OffsetEstimator();
        estimator.add(EPOCH, EPOCH + 7, EPOCH);
        assertEquals(Optional.of(new Estimate(7, 1)), estimator.estimate(), "the error bound is at least 1 ns");
        for (int i = 0; i < OffsetEstimator.WINDOW; i++) {
            estimator.add(EPOCH, EPOCH + 1_000 + 3_000, EPOCH + 2_000);
        }
        assertEquals(Optional.of(new Estimate(3_000, 1_000)), estimator.estimate());
        estimator.clear();
        assertEquals(Optional.empty(), estimator.estimate());
    }

    @Test
    void oddDifferencesRoundTowardsTheMiddle() {
        OffsetEstimator estimator = new OffsetEstimator();
        // (3 + 0) / 2 = 1.5: 1 or 2, within the bound of 2 either way
        Estimate estimate = estimator.add(EPOCH, EPOCH + 3, EPOCH + 3).orElseThrow();
        assertEquals(2, estimate.errorNanos());
        assertEquals(1, estimate.offsetNanos());
    }
}
