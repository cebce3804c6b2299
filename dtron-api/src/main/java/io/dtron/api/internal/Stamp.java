package io.dtron.api.internal;

import java.util.Objects;

/**
 * Not API. What a {@code Sync} carries besides the channel and its variables, as on the wire: an event time of 0
 * means "the publish time", and "" and 0 mean "none".
 *
 * @param sender           the publishing member's id
 * @param sequence         the sender's sequence number, from 1
 * @param publishTimeNanos the sender's wall clock when publishing, ns since the epoch
 * @param eventTimeNanos   the sender's wall clock when the event happened, ns since the epoch; 0 for the publish time
 * @param runId            the run the message belongs to, or ""
 * @param ackedSender      on an acknowledgement or pong, the sender of the message it answers, else ""
 * @param ackedSequence    on an acknowledgement or pong, the sequence number of the message it answers, else 0
 * @param clockOffsetNanos the sender's estimate of (tester's clock - own clock), 0 if none
 * @param clockErrorNanos  the error bound of that estimate, 0 if none
 */
public record Stamp(String sender, long sequence, long publishTimeNanos, long eventTimeNanos, String runId,
        String ackedSender, long ackedSequence, long clockOffsetNanos, long clockErrorNanos) {

    /** No sender, no times: a message made locally, not received. */
    public static final Stamp NONE = new Stamp("", 0, 0, 0, "", "", 0, 0, 0);

    /** Checks the strings. */
    public Stamp {
        Objects.requireNonNull(sender, "sender");
        Objects.requireNonNull(runId, "runId");
        Objects.requireNonNull(ackedSender, "ackedSender");
    }

    /** Returns the event time, or the publish time if none was given. */
    public long effectiveEventTimeNanos() {
        return eventTimeNanos != 0 ? eventTimeNanos : publishTimeNanos;
    }
}
