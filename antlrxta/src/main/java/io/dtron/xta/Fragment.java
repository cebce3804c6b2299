package io.dtron.xta;

import java.util.Objects;

/**
 * A piece of model text that is parsed on its own: a whole {@code .xta} file, or one element or label of an
 * XML model. It knows where its characters stand in the file, so that every position inside it can be
 * reported as file, line and column, and, for XML labels, as the template, the label kind and the column
 * inside the label.
 */
public final class Fragment {
    private final String file;
    private final String template;
    private final String kind;
    private final String text;
    private final LineMap fileLines;
    private final int[] fileOffsets;

    private Fragment(String file, String template, String kind, String text, LineMap fileLines, int[] fileOffsets) {
        this.file = Objects.requireNonNull(file, "file");
        this.template = template;
        this.kind = kind;
        this.text = Objects.requireNonNull(text, "text");
        this.fileLines = Objects.requireNonNull(fileLines, "fileLines");
        this.fileOffsets = fileOffsets;
    }

    /** A whole text file: its offsets are the file's offsets. */
    public static Fragment ofFile(String file, String text) {
        return new Fragment(file, null, null, text, LineMap.of(text), null);
    }

    /**
     * A part of a file whose decoded characters stand at the given file offsets (entity references make the
     * two differ). {@code fileOffsets} has one entry per character of {@code text}, plus one for its end.
     */
    public static Fragment ofPart(String file, String template, String kind, String text, LineMap fileLines,
                                  int[] fileOffsets) {
        if (fileOffsets.length != text.length() + 1) {
            throw new IllegalArgumentException("need one file offset per character plus one");
        }
        return new Fragment(file, template, kind, text, fileLines, fileOffsets.clone());
    }

    /** The same text attributed to {@code template} (for a template's name, read before it is known). */
    public Fragment withTemplate(String template) {
        return new Fragment(file, template, kind, text, fileLines, fileOffsets);
    }

    /** The file name as the user gave it. */
    public String file() {
        return file;
    }

    /** The template this fragment belongs to, or null for global text. */
    public String template() {
        return template;
    }

    /** The kind of label or element ({@code guard}, {@code declaration}, ...), or null for a whole file. */
    public String kind() {
        return kind;
    }

    /** The text that is parsed. */
    public String text() {
        return text;
    }

    /** Whether this fragment is a part of a larger file (an XML element or label). */
    public boolean isPart() {
        return fileOffsets != null;
    }

    /** The offset in the file of the character at {@code offset} in this fragment. */
    public int fileOffset(int offset) {
        int clamped = Math.max(0, Math.min(offset, text.length()));
        return fileOffsets == null ? clamped : fileOffsets[clamped];
    }

    /** The 1-based line in the file of the character at {@code offset}. */
    public int line(int offset) {
        return fileLines.line(fileOffset(offset));
    }

    /** The 1-based column in the file of the character at {@code offset}. */
    public int column(int offset) {
        return fileLines.column(fileOffset(offset));
    }

    @Override
    public String toString() {
        return file + (template == null ? "" : " template " + template) + (kind == null ? "" : " " + kind);
    }
}
