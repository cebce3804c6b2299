package io.dtron.bridge;

import java.util.Arrays;

/**
 * The latency of bus messages: the receive time t2 minus the publish time t1, in microseconds, over
 * {@code count} messages. Percentiles are nearest-rank. t1 is the sender's wall clock and t2 the receiver's, so
 * across hosts the figures include the difference of their clocks.
 *
 * @param count     the number of messages
 * @param minMicros the smallest latency, 0 when there were no messages
 * @param p50Micros the median
 * @param p99Micros the 99th percentile
 * @param maxMicros the largest latency
 */
public record LatencySummary(long count, long minMicros, long p50Micros, long p99Micros, long maxMicros) {

    /** The summary of the given latencies in microseconds (the array is not changed). */
    public static LatencySummary of(long[] latenciesMicros) {
        if (latenciesMicros.length == 0) {
            return new LatencySummary(0, 0, 0, 0, 0);
        }
        long[] sorted = latenciesMicros.clone();
        Arrays.sort(sorted);
        return new LatencySummary(sorted.length, sorted[0], rank(sorted, 50), rank(sorted, 99),
                sorted[sorted.length - 1]);
    }

    private static long rank(long[] sorted, int percent) {
        int index = (int) Math.ceil(percent / 100.0 * sorted.length) - 1;
        return sorted[Math.max(0, index)];
    }

    @Override
    public String toString() {
        if (count == 0) {
            return "count 0";
        }
        return "count " + count + ", min " + minMicros + " us, p50 " + p50Micros + " us, p99 " + p99Micros
                + " us, max " + maxMicros + " us";
    }
}
