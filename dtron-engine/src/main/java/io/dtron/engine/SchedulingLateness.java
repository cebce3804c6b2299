package io.dtron.engine;

import io.dtron.engine.internal.clock.RealClock;

/**
 * How late this machine wakes up a tester in real time: measured by waiting exactly as a real-time run waits for its
 * next action (sleeping, then spinning the last stretch).
 */
public final class SchedulingLateness {
    private SchedulingLateness() {
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
