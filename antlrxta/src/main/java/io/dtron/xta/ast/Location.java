package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;

/**
 * A location of a template.
 *
 * @param pos       where it was declared
 * @param id        the XML id (the name in XTA files)
 * @param name      the name, or null for an anonymous location of an XML model
 * @param kind      normal, urgent or committed
 * @param invariant the invariant, or null
 * @param coord     the drawing position, or null
 * @param labels    the name and labels as drawn (kind {@code name}, {@code invariant}, {@code comments}...)
 */
public record Location(Pos pos, String id, String name, Kind kind, Expr invariant, Coord coord, List<Label> labels) {
    public Location {
        labels = List.copyOf(labels);
    }

    /** Normal, urgent (no delay) or committed (no delay, and the next move leaves a committed location). */
    public enum Kind { NORMAL, URGENT, COMMITTED }
}
