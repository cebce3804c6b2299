package io.dtron.api;

import java.util.Objects;

/**
 * How long the messages of one member took to reach the tester, from {@link
 * io.dtron.api.internal.TesterSide#getDelaysFromMembers()}: from
 * the sender's publish time, corrected by the clock offset the sender estimated, to the tester's receive time, over
 * every message that carried an offset estimate (pings and pongs included). Immutable.
 *
 * @param member        the sending member
 * @param count         how many messages were measured
 * @param minNanos      the shortest delay, in nanoseconds (0 when the clocks' error made it look negative)
 * @param maxNanos      the longest delay, in nanoseconds
 * @param lastNanos     the delay of the last message measured
 * @param maxErrorNanos the largest error bound of the offset estimates used: each delay is exact within it
 */
public record MemberDelay(String member, long count, long minNanos, long maxNanos, long lastNanos,
        long maxErrorNanos) {

    /**
     * Checks the values.
     *
     * @throws IllegalArgumentException if a value is negative, or the minimum exceeds the maximum
     */
    public MemberDelay {
        Objects.requireNonNull(member, "member");
        if (count < 1 || minNanos < 0 || lastNanos < 0 || maxErrorNanos < 0 || minNanos > maxNanos) {
            throw new IllegalArgumentException("not a delay summary: " + count + " messages, " + minNanos + ".."
                    + maxNanos + " ns, last " + lastNanos + " ns, error " + maxErrorNanos + " ns");
        }
    }

    /** Adds the delay of one more message. */
    MemberDelay plus(long delayNanos, long errorNanos) {
        long delay = Math.max(0, delayNanos);
        return new MemberDelay(member, count + 1, Math.min(minNanos, delay), Math.max(maxNanos, delay), delay,
                Math.max(maxErrorNanos, errorNanos));
    }

    /** The summary of one message's delay. */
    static MemberDelay first(String member, long delayNanos, long errorNanos) {
        long delay = Math.max(0, delayNanos);
        return new MemberDelay(member, 1, delay, delay, delay, errorNanos);
    }
}
