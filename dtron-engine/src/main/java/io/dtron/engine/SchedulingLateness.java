package io.dtron.engine;

import io.dtron.engine.internal.clock.RealClock;

/**
 * How late this machine wakes up a tester in real time: measured by waiting exactly as a real-time run waits for its
 * next action (sleeping, then spinning the last stretch).
 */
public final class SchedulingLateness {
    /**
     * The waits {@link #measureMicros()} measures, in microseconds: short ones, and longer ones after which a busy
     * machine wakes later.
     */
    private static final long[] WAITS_MICROS = {500, 500, 500, 500, 2000, 5000, 500, 500, 10_000, 500, 500, 20_000};
    private static final int ROUNDS = 4;

    private SchedulingLateness() {
    }

    /**
     * Measures before a real-time run: {@value #ROUNDS} rounds of waits of 0.5 to 20 ms, about 160 ms in all, as the
     * tester waits; returns the latest wake-up after a wait's target, in microseconds.
     */
    public static long measureMicros() {
        return worstMicros(WAITS_MICROS, ROUNDS);
    }

    /**
     * The input margin a real-time run needs on a machine that wakes its tester up to {@code worstMicros} late: twice
     * that, and never less than {@link TestOptions#DEFAULT_INPUT_MARGIN_MICROS}.
     */
    public static long inputMarginMicros(long worstMicros) {
        return Math.max(TestOptions.DEFAULT_INPUT_MARGIN_MICROS, 2 * Math.max(0, worstMicros));
    }

    /**
     * Waits {@code rounds} times for each of {@code waitsMicros} in turn, as a real-time run waits, and returns the
     * latest wake-up after a wait's target, in microseconds (0 if every wait ended on time).
     */
    public static long worstMicros(long[] waitsMicros, int rounds) {
        RealClock clock = new RealClock();
        clock.begin(java.util.OptionalLong.empty());
        long worst = 0;
        for (int round = 0; round < rounds; round++) {
            for (long wait : waitsMicros) {
                long target = clock.nowMicros() + wait;
                clock.awaitUntil(target);
                worst = Math.max(worst, clock.nowMicros() - target);
            }
        }
        return worst;
    }
}
