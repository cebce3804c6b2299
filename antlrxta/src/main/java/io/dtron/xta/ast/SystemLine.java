package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;

/**
 * {@code system A, B < C;}: the processes of the network in priority levels, lowest first.
 *
 * @param pos    where it was written
 * @param levels each level's names with their positions
 */
public record SystemLine(Pos pos, List<List<Name>> levels) {
    public SystemLine {
        levels = levels.stream().map(List::copyOf).toList();
    }

    /** A name with its position. */
    public record Name(Pos pos, String name) {
    }
}
