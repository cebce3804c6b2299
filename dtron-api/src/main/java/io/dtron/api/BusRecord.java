package io.dtron.api;

import java.util.Map;
import java.util.Objects;

/**
 * One message as a member received it from the bus, with everything its sender stamped on it and its receive time,
 * for traces: {@link Dtron#addRecordListener} hands every message out in the bus's order, DTRON's own (starts,
 * acknowledgements, pings, ...) included. Immutable.
 *
 * @param channel          the channel (bus group)
 * @param sender           the member that published it
 * @param sequence         the sender's sequence number (0 from senders that number none)
 * @param publishTimeNanos the sender's wall clock when it published, ns since the epoch
 * @param eventTimeNanos   when the event happened on the sender's clock (the publish time if it gave none)
 * @param receiveTimeNanos this member's wall clock when it arrived
 * @param runId            the run it belongs to, or ""
 * @param ackedSender      on an acknowledgement or pong, the sender of the message it answers, else ""
 * @param ackedSequence    on an acknowledgement or pong, that message's sequence number, else 0
 * @param clockOffsetNanos the sender's estimate of the tester's clock minus its own (0 if none)
 * @param clockErrorNanos  that estimate's error bound (0 if none)
 * @param variables        the values of the channel's variables, by name
 */
public record BusRecord(String channel, String sender, long sequence, long publishTimeNanos, long eventTimeNanos,
        long receiveTimeNanos, String runId, String ackedSender, long ackedSequence, long clockOffsetNanos,
        long clockErrorNanos, Map<String, Integer> variables) {

    /** Checks the strings and copies the variables. */
    public BusRecord {
        Objects.requireNonNull(channel, "channel");
        Objects.requireNonNull(sender, "sender");
        Objects.requireNonNull(runId, "runId");
        Objects.requireNonNull(ackedSender, "ackedSender");
        variables = Map.copyOf(variables);
    }
}
