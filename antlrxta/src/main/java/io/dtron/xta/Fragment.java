package io.dtron.xta;

import io.dtron.xta.internal.XtaPlaces;
import java.util.Arrays;
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
    /** Where the runs of consecutive file offsets start in the text, or null for a whole file. */
    private final int[] runStarts;
    /** The file offset of each run's first character. */
    private final int[] runFileStarts;
    /** For an .xta file: where its templates and labels stand, found at the first question; else null. */
    private final boolean xta;
    private XtaPlaces places;

    private Fragment(String file, String template, String kind, String text, LineMap fileLines, int[] runStarts,
                     int[] runFileStarts) {
        this(file, template, kind, text, fileLines, runStarts, runFileStarts, false);
    }

    private Fragment(String file, String template, String kind, String text, LineMap fileLines, int[] runStarts,
                     int[] runFileStarts, boolean xta) {
        this.file = Objects.requireNonNull(file, "file");
        this.template = template;
        this.kind = kind;
        this.text = Objects.requireNonNull(text, "text");
        this.fileLines = Objects.requireNonNull(fileLines, "fileLines");
        this.runStarts = runStarts;
        this.runFileStarts = runFileStarts;
        this.xta = xta;
    }

    /** A whole text file: its offsets are the file's offsets. */
    public static Fragment ofFile(String file, String text) {
        return new Fragment(file, null, null, text, LineMap.of(text), null, null);
    }

    /**
     * A whole {@code .xta} (or {@code .ta}) file: as {@link #ofFile}, and a position in it knows its template and
     * label ({@link #templateAt}, {@link #kindAt}).
     */
    public static Fragment ofXtaFile(String file, String text) {
        return new Fragment(file, null, null, text, LineMap.of(text), null, null, true);
    }

    /**
     * A part of a file whose decoded characters stand at the given file offsets (entity references make the
     * two differ). {@code fileOffsets} has one entry per character of {@code text}, plus one for its end.
     */
    public static Fragment ofPart(String file, String template, String kind, String text, LineMap fileLines,
                                  Offsets fileOffsets) {
        if (fileOffsets.count != text.length() + 1) {
            throw new IllegalArgumentException("need one file offset per character plus one");
        }
        return new Fragment(file, template, kind, text, fileLines, Arrays.copyOf(fileOffsets.starts, fileOffsets.runs),
                Arrays.copyOf(fileOffsets.fileStarts, fileOffsets.runs));
    }

    /**
     * The file offsets of a part's characters, given one by one and kept as runs of consecutive offsets: a part
     * needs memory for each place where its text and the file's differ (an entity reference, a CDATA section,
     * a {@code \r\n}), not for each character.
     */
    public static final class Offsets {
        private int[] starts = new int[4];
        private int[] fileStarts = new int[4];
        private int runs;
        private int count;
        private int nextFileOffset;

        /** Adds the file offset of the next character (or, last, of the part's end). */
        public void add(int fileOffset) {
            if (runs == 0 || fileOffset != nextFileOffset) {
                if (runs == starts.length) {
                    starts = Arrays.copyOf(starts, runs * 2);
                    fileStarts = Arrays.copyOf(fileStarts, runs * 2);
                }
                starts[runs] = count;
                fileStarts[runs] = fileOffset;
                runs++;
            }
            count++;
            nextFileOffset = fileOffset + 1;
        }
    }

    /** The same text attributed to {@code template} (for a template's name, read before it is known). */
    public Fragment withTemplate(String template) {
        return new Fragment(file, template, kind, text, fileLines, runStarts, runFileStarts, xta);
    }

    /** The template of the character at {@code offset}: this fragment's, or in an .xta file the one around it. */
    public String templateAt(int offset) {
        XtaPlaces.Place place = placeAt(offset);
        return place != null ? place.template() : template;
    }

    /**
     * The kind of label or element of the character at {@code offset}: this fragment's, or in an .xta file that of
     * the label around it ({@code guard}, {@code invariant}, {@code declaration}, ...), or null.
     */
    public String kindAt(int offset) {
        XtaPlaces.Place place = placeAt(offset);
        return place != null ? place.kind() : kind;
    }

    private XtaPlaces.Place placeAt(int offset) {
        if (!xta) {
            return null;
        }
        synchronized (this) {
            if (places == null) {
                places = XtaPlaces.of(text);
            }
        }
        return places.at(offset);
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
        return runStarts != null;
    }

    /** The offset in the file of the character at {@code offset} in this fragment. */
    public int fileOffset(int offset) {
        int clamped = Math.max(0, Math.min(offset, text.length()));
        if (runStarts == null) {
            return clamped;
        }
        int run = Arrays.binarySearch(runStarts, clamped);
        if (run < 0) {
            run = -run - 2;
        }
        return runFileStarts[run] + clamped - runStarts[run];
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
