package io.dtron.troninstaller;

/**
 * Uppaal TRON is not installed where DTRON looks for it. The message says where DTRON looked, that TRON is not
 * bundled (its licence forbids redistribution) and how to install it.
 */
public final class TronNotFoundException extends Exception {
    private static final long serialVersionUID = 1L;

    /** An exception with the full, user-facing message. */
    public TronNotFoundException(String message) {
        super(message);
    }
}
