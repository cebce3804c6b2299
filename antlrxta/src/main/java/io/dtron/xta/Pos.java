package io.dtron.xta;

/**
 * A range of characters in a {@link Fragment}: where a piece of the model was written.
 *
 * @param fragment the text it was parsed from
 * @param start    offset of its first character in the fragment
 * @param end      offset after its last character
 */
public record Pos(Fragment fragment, int start, int end) {

    /** The 1-based line in the file. */
    public int line() {
        return fragment.line(start);
    }

    /** The 1-based column in the file. */
    public int column() {
        return fragment.column(start);
    }

    /** The 1-based column inside the fragment's text (for XML labels: the position inside the label). */
    public int columnInFragment() {
        int lineStart = fragment.text().lastIndexOf('\n', Math.max(0, start - 1)) + 1;
        return start - lineStart + 1;
    }

    /** The source text of this range. */
    public String text() {
        String t = fragment.text();
        return t.substring(Math.max(0, Math.min(start, t.length())), Math.max(0, Math.min(end, t.length())));
    }

    /** A range that covers this one and {@code other}. */
    public Pos to(Pos other) {
        return new Pos(fragment, Math.min(start, other.start), Math.max(end, other.end));
    }

    @Override
    public String toString() {
        return fragment.file() + ":" + line() + ":" + column();
    }
}
