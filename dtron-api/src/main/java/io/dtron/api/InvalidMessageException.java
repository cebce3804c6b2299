package io.dtron.api;

import java.util.Objects;

/** A message or a set of values that does not fit its channel, with the reason why. */
public final class InvalidMessageException extends IllegalArgumentException {
    private static final long serialVersionUID = 1L;

    /** Why a message was rejected. */
    public enum Reason {
        /** The bytes are no valid {@code Sync} message. */
        MALFORMED,
        /** The message names a channel that is not known here. */
        UNKNOWN_CHANNEL,
        /** The message carries variables the channel does not have. */
        UNKNOWN_VARIABLES,
        /** The message lacks variables the channel has. */
        MISSING_VARIABLES,
        /** The message carries no valid code of the bus's secret (security.md); dropped by the transport. */
        UNAUTHENTICATED,
        /**
         * The message was sent again (over NATS its sender's counter was used already, over JGroups its connection
         * was recorded earlier); dropped by the transport.
         */
        REPLAYED,
        /** The message's sender time is too far from the bus's time of it; dropped by the transport. */
        STALE
    }

    private final Reason reason;

    /**
     * Creates the exception.
     *
     * @param reason  why the message does not fit
     * @param message what exactly is wrong, for a log
     */
    public InvalidMessageException(Reason reason, String message) {
        super(message);
        this.reason = Objects.requireNonNull(reason, "reason");
    }

    /** Returns why the message does not fit. */
    public Reason getReason() {
        return reason;
    }
}
