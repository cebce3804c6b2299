package io.dtron.engine;

/**
 * The model loads, but uses something the engine cannot run (stopwatches, priorities, CSP synchronisation,
 * clock guards on broadcast receivers), or cannot start (an initial value that cannot be computed). The
 * message says what and where.
 */
public final class UnsupportedModelException extends RuntimeException {
    private static final long serialVersionUID = 1L;

    /** An exception with a message for the model's author. */
    public UnsupportedModelException(String message) {
        super(message);
    }
}
