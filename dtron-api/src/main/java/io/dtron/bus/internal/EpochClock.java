package io.dtron.bus.internal;

import java.time.Instant;

/** Not API. The wall clock in nanoseconds since the epoch, as used for publish and receive times. */
public final class EpochClock {
    private EpochClock() {
    }

    /** Returns the current wall-clock time in nanoseconds since the epoch (microsecond resolution on Linux). */
    public static long nowNanos() {
        Instant now = Instant.now();
        return Math.addExact(Math.multiplyExact(now.getEpochSecond(), 1_000_000_000L), now.getNano());
    }
}
