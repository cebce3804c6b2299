package io.dtron.api;

import java.util.Map;

/**
 * One message of a channel: its variable values and, for a message received
 * from the bus, who sent it and when. Immutable; equal when all of that is equal.
 */
public interface IDtronChannelValued extends IChannelSkeleton {

    /** Returns the template this message belongs to. */
    IDtronChannel getChannel();

    /** Returns the values by variable name, in the template's order; immutable. */
    Map<String, Integer> getVariables();

    /** Returns the id of the member that published the message, or "" if it was not received from the bus. */
    String getSender();

    /** Returns the sender's sequence number of the message (from 1), or 0 if unknown. */
    long getSequence();

    /** Returns the sender's wall-clock publish time in nanoseconds since the epoch, or 0 if unknown. */
    long getPublishTimeNanos();

    /** Returns this member's wall-clock receive time in nanoseconds since the epoch, or 0 if not received. */
    long getReceiveTimeNanos();

    /** Encodes the channel name and values as a {@code Sync} protocol-buffer message. */
    byte[] toByteArray();
}
