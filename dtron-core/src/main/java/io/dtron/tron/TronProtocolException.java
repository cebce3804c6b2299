package io.dtron.tron;

import java.io.IOException;

/**
 * A violation of TRON's socket-adapter protocol (an unknown command, a truncated frame, an event on a channel that
 * was never registered, a connection dropped in the middle of a frame) or an error code the other side replied
 * with. The message says what was wrong in terms a user can act on.
 */
public class TronProtocolException extends IOException {
    private static final long serialVersionUID = 1L;

    private final int errorCode;

    /** A protocol violation. */
    public TronProtocolException(String message) {
        this(message, 0);
    }

    /** A negative error code from the tester, with its explanation in the message. */
    public TronProtocolException(String message, int errorCode) {
        super(message);
        this.errorCode = errorCode;
    }

    /** The tester's error code (negative), or 0 when this is not a refused request. */
    public int errorCode() {
        return errorCode;
    }
}
