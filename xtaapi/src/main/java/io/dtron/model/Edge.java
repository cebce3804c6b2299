package io.dtron.model;

import io.dtron.xta.Pos;
import java.util.List;

/**
 * An edge of a process. Its select bindings take frame slots 0..selects-1; quantifiers inside its labels
 * take further slots, up to {@code frameSize}.
 *
 * @param index     its number within the process
 * @param source    the source location's index
 * @param target    the target location's index
 * @param selects   the select bindings
 * @param guard     the guard (data and clock constraints), or null
 * @param sync      the synchronisation, or null
 * @param updates   the updates, in order
 * @param frameSize the frame slots its labels need
 * @param pos       where it was declared
 */
public record Edge(int index, int source, int target, List<Select> selects, Expression guard, Sync sync,
                   List<Expression> updates, int frameSize, Pos pos) {
    public Edge {
        selects = List.copyOf(selects);
        updates = List.copyOf(updates);
    }

    /** {@code name : type}: the edge exists once for each value {@code lower..upper} bound to {@code slot}. */
    public record Select(String name, int slot, Type type, int lower, int upper) {
    }

    /** A synchronisation on the channel the expression evaluates to. */
    public record Sync(Expression channel, Direction direction) {
    }

    /** Send ({@code c!}), receive ({@code c?}) or CSP-style ({@code c}). */
    public enum Direction { SEND, RECEIVE, CSP }
}
