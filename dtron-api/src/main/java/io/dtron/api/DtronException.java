package io.dtron.api;

/** The bus failed: a {@link Dtron} could not connect, or could not hand a message to the bus. */
public final class DtronException extends RuntimeException {
    private static final long serialVersionUID = 1L;

    /**
     * Creates the exception.
     *
     * @param message what failed
     * @param cause   the transport's exception
     */
    public DtronException(String message, Throwable cause) {
        super(message, cause);
    }
}
