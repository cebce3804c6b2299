package io.dtron.model;

import io.dtron.xta.Pos;

/**
 * A location of a process.
 *
 * @param index     its number within the process
 * @param name      its name ({@code _id3} style for anonymous locations, after their XML id)
 * @param kind      normal, urgent or committed
 * @param invariant the invariant, or null
 * @param frameSize the frame slots the invariant's quantifiers need
 * @param pos       where it was declared
 */
public record Location(int index, String name, Kind kind, Expression invariant, int frameSize, Pos pos) {

    /** Normal, urgent (time cannot pass) or committed (time cannot pass and it must be left first). */
    public enum Kind { NORMAL, URGENT, COMMITTED }

    /** Whether time may not pass while a process is here. */
    public boolean isUrgentOrCommitted() {
        return kind != Kind.NORMAL;
    }
}
