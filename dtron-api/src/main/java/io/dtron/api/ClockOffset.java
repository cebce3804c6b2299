package io.dtron.api;

import java.util.Objects;

/**
 * A member's estimate of how far the tester's wall clock is from its own, from {@link Dtron#getClockOffset()}: the
 * tester's clock reads {@code offsetNanos} more than this member's, give or take {@code errorNanos}.
 *
 * @param tester      the member id of the tester the estimate is for
 * @param offsetNanos the tester's wall clock minus this member's, in nanoseconds; 0 on the tester itself
 * @param errorNanos  the error bound in nanoseconds: half the round trip of the ping the estimate comes from (the
 *                    true offset lies within it), at least 1; 0 on the tester itself, whose offset is exact
 */
public record ClockOffset(String tester, long offsetNanos, long errorNanos) {

    /**
     * Checks the values.
     *
     * @throws IllegalArgumentException if the error bound is negative
     */
    public ClockOffset {
        Objects.requireNonNull(tester, "tester");
        if (errorNanos < 0) {
            throw new IllegalArgumentException("negative error bound: " + errorNanos);
        }
    }

    /** Returns {@code ownEpochNanos}, a time on this member's wall clock, as a time on the tester's. */
    public long toTesterNanos(long ownEpochNanos) {
        return ownEpochNanos + offsetNanos;
    }
}
