package io.dtron.bus.internal;

import java.util.Arrays;
import java.util.Objects;

/**
 * One message as received from the bus: immutable.
 *
 * <p>The receive time is taken on the wall clock in nanoseconds since the
 * epoch when the transport handed the message over, so that it can be set
 * against the publish time carried inside the payload.
 */
public final class BusMessage {
    private final String group;
    private final byte[] payload;
    private final String sender;
    private final long receiveTimeNanos;

    /**
     * Creates a message.
     *
     * @param group            the group it was published on
     * @param payload          its bytes (copied)
     * @param sender           the id of the member that published it
     * @param receiveTimeNanos when it arrived, in nanoseconds since the epoch
     */
    public BusMessage(String group, byte[] payload, String sender, long receiveTimeNanos) {
        this.group = Objects.requireNonNull(group, "group");
        this.payload = Objects.requireNonNull(payload, "payload").clone();
        this.sender = Objects.requireNonNull(sender, "sender");
        this.receiveTimeNanos = receiveTimeNanos;
    }

    /** Returns the group the message was published on. */
    public String group() {
        return group;
    }

    /** Returns a copy of the payload. */
    public byte[] payload() {
        return payload.clone();
    }

    /** Returns the payload's length in bytes. */
    public int payloadLength() {
        return payload.length;
    }

    /** Returns the id of the member that published the message. */
    public String sender() {
        return sender;
    }

    /** Returns when the message arrived, in nanoseconds since the epoch. */
    public long receiveTimeNanos() {
        return receiveTimeNanos;
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof BusMessage other
                && group.equals(other.group)
                && Arrays.equals(payload, other.payload)
                && sender.equals(other.sender)
                && receiveTimeNanos == other.receiveTimeNanos;
    }

    @Override
    public int hashCode() {
        return Objects.hash(group, Arrays.hashCode(payload), sender, receiveTimeNanos);
    }

    @Override
    public String toString() {
        return "BusMessage{group=" + group + ", sender=" + sender + ", " + payload.length + " bytes, received="
                + receiveTimeNanos + "}";
    }
}
