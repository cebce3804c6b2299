package io.dtron.bridge;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.util.stream.LongStream;
import org.junit.jupiter.api.Test;

class LatencySummaryTest {

    @Test
    void percentilesAreNearestRank() {
        long[] latencies = LongStream.rangeClosed(1, 1000).map(i -> 1001 - i).toArray();
        LatencySummary summary = LatencySummary.of(latencies);
        assertEquals(new LatencySummary(1000, 1, 500, 990, 1000), summary);
        assertEquals(1000, latencies[0], "the input is not sorted in place");
        assertEquals("count 1000, min 1 us, p50 500 us, p99 990 us, max 1000 us", summary.toString());
    }

    @Test
    void fewAndNoMessages() {
        assertEquals(new LatencySummary(1, 7, 7, 7, 7), LatencySummary.of(new long[] {7}));
        assertEquals(new LatencySummary(3, 1, 2, 3, 3), LatencySummary.of(new long[] {3, 1, 2}));
        assertEquals("count 0", LatencySummary.of(new long[0]).toString());
    }
}
