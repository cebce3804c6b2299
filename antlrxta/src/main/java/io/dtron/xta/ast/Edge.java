package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;

/**
 * An edge of a template with its five kinds of labels.
 *
 * @param pos     where it was written
 * @param source  the source location's id
 * @param target  the target location's id
 * @param selects select bindings, possibly empty
 * @param guard   the guard, or null
 * @param sync    the synchronisation, or null
 * @param updates the update expressions, possibly empty
 * @param probability the weight of an edge leaving a branchpoint (statistical model checking), or null
 * @param nails   the drawing's bend points
 * @param labels  the labels' raw texts and drawing positions
 */
public record Edge(Pos pos, String source, String target, List<Select> selects, Expr guard, Sync sync,
                   List<Expr> updates, Expr probability, List<Coord> nails, List<Label> labels) {
    public Edge {
        selects = List.copyOf(selects);
        updates = List.copyOf(updates);
        nails = List.copyOf(nails);
        labels = List.copyOf(labels);
    }

    /** {@code name : type} of a select label. */
    public record Select(Pos pos, String name, TypeExpr type) {
    }

    /** {@code c!}, {@code c?} or a CSP-style {@code c}. */
    public record Sync(Pos pos, Expr channel, Direction direction) {
    }

    /** The direction of a synchronisation. */
    public enum Direction { SEND, RECEIVE, CSP }
}
