package io.dtron.bridge;

import java.util.Objects;

/**
 * The delays of one channel's messages in a run, in one direction, on the run's clock: for an input, from the
 * tester publishing it to an adapter applying it (its acknowledgement's time); for an output, from the system
 * producing it (the time its adapter stamped) to the tester receiving it. The delay interval of thesis section 3.5
 * that a Delta-extended model takes into account. Immutable.
 *
 * @param channel    the channel's name on the bus
 * @param direction  {@code "input"} or {@code "output"}
 * @param count      how many messages were measured
 * @param lowMicros  the shortest delay, in microseconds
 * @param highMicros the longest delay, in microseconds
 */
public record ChannelDelay(String channel, String direction, long count, long lowMicros, long highMicros) {

    /**
     * Checks the values.
     *
     * @throws IllegalArgumentException if the direction is neither, a value is negative, or low exceeds high
     */
    public ChannelDelay {
        Objects.requireNonNull(channel, "channel");
        if (!direction.equals("input") && !direction.equals("output")) {
            throw new IllegalArgumentException("direction must be input or output: " + direction);
        }
        if (count < 1 || lowMicros < 0 || lowMicros > highMicros) {
            throw new IllegalArgumentException("not a delay interval: " + count + " messages, " + lowMicros + ".."
                    + highMicros + " us");
        }
    }

    /** This interval with one more delay in it. */
    ChannelDelay plus(long delayMicros) {
        long delay = Math.max(0, delayMicros);
        return new ChannelDelay(channel, direction, count + 1, Math.min(lowMicros, delay), Math.max(highMicros, delay));
    }
}
