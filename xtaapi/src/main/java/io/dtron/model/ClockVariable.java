package io.dtron.model;

import io.dtron.xta.Pos;

/**
 * A clock or clock array: global, or local to one process. Clocks are numbered from 1 (0 is the reference
 * clock of zones).
 *
 * @param name  the qualified name
 * @param type  {@link Type.Clock} or an array of clocks
 * @param index the number of its first clock
 * @param owner the owning process's name, or null
 * @param pos   where it was declared
 */
public record ClockVariable(String name, Type type, int index, String owner, Pos pos) {

    /** The name of the clock at {@code index} (an element for arrays), e.g. {@code x} or {@code T[1]}. */
    public String elementName(int clockIndex) {
        return Names.element(name, type, clockIndex - index, Type::clocks);
    }
}
