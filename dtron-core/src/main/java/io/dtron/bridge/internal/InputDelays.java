package io.dtron.bridge.internal;

import io.dtron.bridge.LatencySummary;
import java.util.ArrayDeque;
import java.util.Collection;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;

/**
 * Not API. How long inputs take to reach the adapters, for the room the tester leaves before an input's window
 * closes: per adapter member, the round trip of the tester's probes before the run (an upper bound of the way
 * there, on the tester's own clock), and per channel, the delays of the inputs the adapters acknowledged, published
 * to applied, each with its clock error. Also says when the probes' round trips have become steady. Thread-safe.
 */
public final class InputDelays {
    /** How many rounds of probes must be steady, compared with as many rounds before them. */
    public static final int STEADY_ROUNDS = 5;
    /** Steady: the last rounds took at most this many times the median of the rounds before them... */
    static final double STEADY_FACTOR = 1.5;
    /** ...or at most this much more, in microseconds (for round trips too short for a factor to mean much). */
    static final long STEADY_SLACK_MICROS = 1000;
    /** How many rounds of probes are compared with as many before them, to tell whether they still get faster. */
    public static final int TREND_ROUNDS = 50;
    /** Still getting faster: the median of the last rounds below this share of the median of the rounds before. */
    static final double IMPROVING = 0.85;
    /** How many acknowledged delays are kept per channel, the latest. */
    private static final int KEPT = 256;

    private final Map<String, Long> probedMicros = new ConcurrentHashMap<>();
    private final Map<String, ArrayDeque<Long>> appliedMicros = new ConcurrentHashMap<>();

    /**
     * Whether round trips (one per round, in order) are steady: there are at least twice {@link #STEADY_ROUNDS}, and
     * the longest of the last {@value #STEADY_ROUNDS} is at most 1.5 times the median of the {@value #STEADY_ROUNDS}
     * before them, or at most 1 ms more than it. A fresh process's first compilations and collections make the first
     * rounds slow and uneven; once they are over, the rounds stay alike.
     */
    public static boolean steady(List<Long> roundsMicros) {
        int n = roundsMicros.size();
        if (n < 2 * STEADY_ROUNDS) {
            return false;
        }
        long[] before = roundsMicros.subList(n - 2 * STEADY_ROUNDS, n - STEADY_ROUNDS).stream()
                .mapToLong(Long::longValue).sorted().toArray();
        long median = before[before.length / 2];
        long last = roundsMicros.subList(n - STEADY_ROUNDS, n).stream().mapToLong(Long::longValue).max().orElse(0);
        return last <= Math.max((long) (STEADY_FACTOR * median), median + STEADY_SLACK_MICROS);
    }

    /**
     * Whether round trips (one per round, in order) no longer get faster: there are at least twice {@value
     * #TREND_ROUNDS}, and the median of the last {@value #TREND_ROUNDS} is at least 0.85 times the median of the
     * {@value #TREND_ROUNDS} before them. A fresh process's code gets faster as the JIT compiler compiles it, over
     * hundreds to thousands of rounds; the rounds only look alike ({@link #steady}) long before that.
     */
    public static boolean noLongerImproving(List<Long> roundsMicros) {
        int n = roundsMicros.size();
        if (n < 2 * TREND_ROUNDS) {
            return false;
        }
        return median(roundsMicros.subList(n - TREND_ROUNDS, n))
                >= IMPROVING * median(roundsMicros.subList(n - 2 * TREND_ROUNDS, n - TREND_ROUNDS));
    }

    private static long median(List<Long> values) {
        long[] sorted = values.stream().mapToLong(Long::longValue).sorted().toArray();
        return sorted[sorted.length / 2];
    }

    /** Records the longest probe round trip of {@code member} in the last rounds before the run. */
    public void probed(String member, long roundTripMicros) {
        probedMicros.put(member, Math.max(0, roundTripMicros));
    }

    /** Records an input on {@code channel} that an adapter applied {@code delayMicros} after it was published. */
    public void applied(String channel, long delayMicros, long errorMicros) {
        ArrayDeque<Long> kept = appliedMicros.computeIfAbsent(channel, c -> new ArrayDeque<>());
        synchronized (kept) {
            if (kept.size() == KEPT) {
                kept.removeFirst();
            }
            kept.addLast(Math.max(0, delayMicros) + Math.max(0, errorMicros));
        }
    }

    /**
     * The room an input on {@code channel} needs, in microseconds: the longer of the probe round trip of its
     * receivers (of every member probed when none is known to receive it) and the 99th percentile of its
     * acknowledged delays with their clock errors; 0 when nothing was measured.
     */
    public long roomMicros(String channel, Collection<String> receivers) {
        long probed = 0;
        for (Map.Entry<String, Long> e : probedMicros.entrySet()) {
            if (receivers.isEmpty() || receivers.contains(e.getKey())) {
                probed = Math.max(probed, e.getValue());
            }
        }
        ArrayDeque<Long> kept = appliedMicros.get(channel);
        if (kept == null) {
            return probed;
        }
        long[] delays;
        synchronized (kept) {
            delays = kept.stream().mapToLong(Long::longValue).toArray();
        }
        return Math.max(probed, LatencySummary.of(delays).p99Micros());
    }
}
