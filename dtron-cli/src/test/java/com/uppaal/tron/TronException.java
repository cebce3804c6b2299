package com.uppaal.tron;

/** The tester refused a registration or the start, with its explanation. */
public class TronException extends RuntimeException {
    private static final long serialVersionUID = 1L;

    /** A refusal, with the tester's explanation. */
    public TronException(String message) {
        super(message);
    }
}
