package io.dtron.engine.internal.sem;

/** The test interface does not split the model into an environment and an implementation. */
public final class PartitionException extends RuntimeException {
    private static final long serialVersionUID = 1L;

    /** An exception with an explanation for the model's author. */
    public PartitionException(String message) {
        super(message);
    }
}
