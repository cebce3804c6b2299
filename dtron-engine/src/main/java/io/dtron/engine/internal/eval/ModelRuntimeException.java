package io.dtron.engine.internal.eval;

import io.dtron.xta.Pos;

/**
 * An error of the model that shows only when it runs: an index out of range, a value outside a variable's
 * range, a division by zero, a failed assertion, an endless loop. The message is written for the model's
 * author; {@link #pos()} says where in the model it happened.
 */
public final class ModelRuntimeException extends RuntimeException {
    private static final long serialVersionUID = 1L;

    private final transient Pos pos;

    /** An error at {@code pos} (may be null when no position is known). */
    public ModelRuntimeException(Pos pos, String message) {
        super(message);
        this.pos = pos;
    }

    /** Where in the model the error happened, or null. */
    public Pos pos() {
        return pos;
    }

    /** The message prefixed with file, line and column, as {@code file:line:column: message}. */
    public String format() {
        return pos == null ? getMessage() : pos + ": " + getMessage();
    }
}
