package io.dtron.model;

import io.dtron.xta.Pos;

/**
 * A variable of the integer state vector (an int, bool, scalar, or an array or struct of them): global, or
 * local to one process.
 *
 * @param name     the qualified name ({@code len}, {@code Gate.list})
 * @param type     its type
 * @param offset   its first slot in the state vector
 * @param initial  its initial values, one per slot
 * @param meta     whether it is a {@code meta} variable (not part of the state for state comparison)
 * @param owner    the owning process's name, or null for a global variable
 * @param pos      where it was declared
 */
public record Variable(String name, Type type, int offset, int[] initial, boolean meta, String owner, Pos pos) {
    public Variable {
        initial = initial.clone();
    }

    /** Its initial values (a copy). */
    @Override
    public int[] initial() {
        return initial.clone();
    }

    /** The number of slots. */
    public int size() {
        return type.slots();
    }
}
