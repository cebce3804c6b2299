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
 * to applied, each with its clock error, and for inputs sent ahead of their time how late after it they were applied.
 * Also says when the probes' round trips have become steady. Thread-safe.
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
    /**
     * The least room, in microseconds, an input sent ahead needs before its window's end: an adapter hands it to its
     * listeners from a spinning thread, and the listener reads the clock for its acknowledgement after that.
     */
    static final long HELD_ROOM_MICROS = 300;

    private final Map<String, Long> probedMicros = new ConcurrentHashMap<>();
    private final Map<String, ArrayDeque<Long>> appliedMicros = new ConcurrentHashMap<>();
    private final Map<String, ArrayDeque<Long>> heldLateMicros = new ConcurrentHashMap<>();

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
        keep(appliedMicros, channel, Math.max(0, delayMicros) + Math.max(0, errorMicros));
    }

    /**
     * Records an input on {@code channel} sent ahead, due at {@code dueMicros}, that an adapter applied at {@code
     * appliedMicros} give or take {@code errorMicros}, {@code sentMicros} being when it was published: how late after
     * its due time it was applied is kept for {@link #heldRoomMicros}; one applied later than that room came later
     * than it was due, and its delay from publication counts as an input's way ({@link #applied}).
     */
    public void appliedAhead(String channel, long sentMicros, long dueMicros, long appliedMicros, long errorMicros) {
        long late = Math.max(0, appliedMicros - dueMicros) + Math.max(0, errorMicros);
        if (late > heldRoomMicros(channel)) {
            applied(channel, appliedMicros - sentMicros, errorMicros);
        }
        keep(heldLateMicros, channel, late);
    }

    private static void keep(Map<String, ArrayDeque<Long>> byChannel, String channel, long micros) {
        ArrayDeque<Long> kept = byChannel.computeIfAbsent(channel, c -> new ArrayDeque<>());
        synchronized (kept) {
            if (kept.size() == KEPT) {
                kept.removeFirst();
            }
            kept.addLast(micros);
        }
    }

    /**
     * The room an input on {@code channel} sent ahead needs before its window's end, in microseconds: the 99th
     * percentile of how late after their due time its inputs were applied, with their clock errors, and at least
     * {@value #HELD_ROOM_MICROS}.
     */
    public long heldRoomMicros(String channel) {
        return Math.max(HELD_ROOM_MICROS, p99(heldLateMicros.get(channel)));
    }

    private static long p99(ArrayDeque<Long> kept) {
        if (kept == null) {
            return 0;
        }
        long[] values;
        synchronized (kept) {
            values = kept.stream().mapToLong(Long::longValue).toArray();
        }
        return values.length == 0 ? 0 : LatencySummary.of(values).p99Micros();
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
        return Math.max(probed, p99(appliedMicros.get(channel)));
    }
}
