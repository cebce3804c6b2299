package io.dtron.model;

import io.dtron.xta.Pos;

/**
 * A location of a process.
 *
 * @param index     its number within the process
 * @param name      its name ({@code _id3} style for anonymous locations, after their XML id)
 * @param kind      normal, urgent, committed or a branchpoint
 * @param invariant the invariant, or null
 * @param frameSize the frame slots the invariant's quantifiers need
 * @param pos       where it was declared
 */
public record Location(int index, String name, Kind kind, Expression invariant, int frameSize, Pos pos) {

    /**
     * Normal, urgent (time cannot pass), committed (time cannot pass and it must be left first) or a branchpoint
     * (statistical model checking: a probabilistic choice among its edges, left at once; the engine does not
     * run models with branchpoints).
     */
    public enum Kind { NORMAL, URGENT, COMMITTED, BRANCHPOINT }

    /** Whether time may not pass while a process is here. */
    public boolean isUrgentOrCommitted() {
        return kind != Kind.NORMAL;
    }
}
