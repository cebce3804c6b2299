package io.dtron.api;

import java.util.Map;

/**
 * One message of a channel: its variable values and, for a message received
 * from the bus, who sent it and when. Immutable; equal when all of that is equal.
 *
 * <p>Times are wall-clock times in nanoseconds since the epoch, each on the
 * clock of the member that took it: the publish and event times on the
 * sender's, the receive time on this member's. A sender that is not the
 * tester also sends its estimate of the difference between the tester's clock
 * and its own ({@link #getClockOffsetNanos()}), so that the tester's time of
 * the event is {@code getEventTimeNanos() + getClockOffsetNanos()}, give or
 * take {@link #getClockErrorNanos()}.
 */
public interface IDtronChannelValued extends IChannelSkeleton {

    /** Returns the template this message belongs to. */
    IDtronChannel getChannel();

    /** Returns the values by variable name, in the template's order; immutable. */
    Map<String, Integer> getVariables();

    /** Returns the id of the member that published the message, or "" if it was not received from the bus. */
    String getSender();

    /**
     * Returns the sender's sequence number of the message (from 1), or 0 if unknown. Each message a member
     * publishes takes the next number, DTRON's own messages (acknowledgements, the clock-offset protocol)
     * included, so a sender's numbers on one channel may skip some.
     */
    long getSequence();

    /** Returns the sender's wall-clock publish time in nanoseconds since the epoch, or 0 if unknown. */
    long getPublishTimeNanos();

    /** Returns this member's wall-clock receive time in nanoseconds since the epoch, or 0 if not received. */
    long getReceiveTimeNanos();

    /**
     * Returns the text the message carries: on {@link Dtron#MODEL_VERSION} the model version handed to a
     * controller, on {@link Dtron#MODEL_OUTCOME} what became of it; "" on every other channel.
     */
    default String getText() {
        return "";
    }

    /**
     * Returns, on a tester's {@link Dtron#RUN_START}, the end of the run it announces (time 0 plus its timeout) on
     * the sender's wall clock, in nanoseconds since the epoch; 0 when it announces none (an older tester, a run of
     * several testers) and on every other message.
     */
    default long getEndTimeNanos() {
        return 0;
    }

    /**
     * Returns, on an input its tester sent ahead of its time, when the input is due on the sender's wall clock, in
     * nanoseconds since the epoch: a member hands it to its listeners then, not before; 0 on every other message.
     */
    default long getDueTimeNanos() {
        return 0;
    }

    /**
     * Returns when the event happened on the sender's wall clock, in nanoseconds since the epoch: for an output
     * when the system produced it (see {@link Dtron#send(IDtronChannelValued, long)}), for an acknowledgement
     * ({@link Dtron#ACK}) when the input was applied. Equals {@link #getPublishTimeNanos()} when the sender gave
     * none (as older senders do); 0 if unknown.
     */
    default long getEventTimeNanos() {
        return getPublishTimeNanos();
    }

    /**
     * Returns the id of the test run the sender stamped on the message (a tester sets it, see {@link
     * io.dtron.api.internal.TesterSide#setRunId}), or "".
     */
    default String getRunId() {
        return "";
    }

    /**
     * Returns, on an acknowledgement ({@link Dtron#ACK}), the sender of the message it acknowledges; "" on other
     * messages.
     */
    default String getAckedSender() {
        return "";
    }

    /**
     * Returns, on an acknowledgement ({@link Dtron#ACK}), the sequence number of the message it acknowledges; 0 on
     * other messages.
     */
    default long getAckedSequence() {
        return 0;
    }

    /**
     * Returns the sender's estimate, when it sent the message, of the tester's clock minus its own clock in
     * nanoseconds; 0 when it had none or is the tester (see {@link Dtron#hasClockOffset()}).
     */
    default long getClockOffsetNanos() {
        return 0;
    }

    /**
     * Returns the error bound of {@link #getClockOffsetNanos()} in nanoseconds: greater than 0 whenever the sender
     * sent an estimate, 0 when it had none or is the tester.
     */
    default long getClockErrorNanos() {
        return 0;
    }

    /** Encodes the message as a {@code Sync} protocol-buffer message: channel name, values, and what it carries. */
    byte[] toByteArray();
}
