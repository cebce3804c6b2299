package io.dtron.xta.internal;

import java.util.ArrayList;
import java.util.List;

/**
 * Not API. Where each part of an {@code .xta} (or Uppaal 3 {@code .ta}) text stands: in which template, and in
 * which label of it (a location's invariant, an edge's select, guard, synchronisation or assignment, the template's
 * declarations), so that an error in such a file is reported with its template and label as one in an XML model
 * is. Found by scanning the text's tokens (comments skipped, braces counted), not by the parser: it holds for text
 * that does not parse.
 */
public final class XtaPlaces {
    /** Where a part stands: its template, and its label kind or null (a location list, the initial location). */
    public record Place(String template, String kind) {
    }

    private record Region(int start, int end, Place place) {
    }

    /** Label regions first (the innermost), then template bodies. */
    private final List<Region> labels = new ArrayList<>();
    private final List<Region> bodies = new ArrayList<>();
    /** The braces of each edge's labels, {@code A -> B { ... }}. */
    private final List<Region> edges = new ArrayList<>();

    private XtaPlaces() {
    }

    /** The places of {@code text}. */
    public static XtaPlaces of(String text) {
        XtaPlaces places = new XtaPlaces();
        places.scan(text);
        return places;
    }

    /** The place of the character at {@code offset}, or null outside every template. */
    public Place at(int offset) {
        for (Region r : labels) {
            if (offset >= r.start && offset <= r.end) {
                return r.place;
            }
        }
        for (Region r : bodies) {
            if (offset >= r.start && offset <= r.end) {
                return r.place;
            }
        }
        return null;
    }

    /** The offset of the opening brace of the edge whose labels hold {@code offset}, or -1 outside every edge. */
    public int edgeAt(int offset) {
        for (Region r : edges) {
            if (offset >= r.start && offset <= r.end) {
                return r.start;
            }
        }
        return -1;
    }

    private void scan(String text) {
        int depth = 0;
        String pending = null; // a template named by "process NAME", its body not yet open
        boolean afterProcess = false;
        String template = null;
        int bodyStart = -1;
        String section = "declaration";
        String label = null; // the kind of the label being read
        int labelStart = -1;
        int edgeStart = -1;
        int i = 0;
        int n = text.length();
        while (i < n) {
            int skipped = afterCommentOrString(text, i);
            if (skipped != i) {
                i = skipped;
                continue;
            }
            char c = text.charAt(i);
            if (Character.isLetter(c) || c == '_') {
                int start = i;
                i = afterWord(text, i, n);
                String word = text.substring(start, i);
                if (depth == 0) {
                    if (afterProcess) {
                        pending = word;
                        afterProcess = false;
                    } else {
                        afterProcess = word.equals("process");
                    }
                } else if (template != null && depth == 1 && isSection(word)) {
                    section = word;
                } else if (template != null && depth == 2 && section.equals("trans") && label == null
                        && edgeLabel(word) != null) {
                    label = edgeLabel(word);
                    labelStart = start;
                }
                continue;
            }
            if (c == '{') {
                if (depth == 0 && pending != null) {
                    template = pending;
                    pending = null;
                    bodyStart = i;
                    section = "declaration";
                } else if (template != null && depth == 1 && section.equals("state")) {
                    label = "invariant";
                    labelStart = i;
                } else if (template != null && depth == 1 && section.equals("trans")) {
                    edgeStart = i;
                }
                depth++;
            } else if (c == '}') {
                depth = Math.max(0, depth - 1);
                if (template != null && label != null && depth == 1) {
                    labels.add(new Region(labelStart, i, new Place(template, label)));
                    label = null;
                }
                if (template != null && edgeStart >= 0 && depth == 1) {
                    edges.add(new Region(edgeStart, i, null));
                    edgeStart = -1;
                }
                if (template != null && depth == 0) {
                    bodies.add(new Region(bodyStart, i, new Place(template, null)));
                    template = null;
                }
            } else if (c == ';') {
                if (template != null && label != null && depth == 2 && !label.equals("invariant")) {
                    labels.add(new Region(labelStart, i, new Place(template, label)));
                    label = null;
                } else if (template != null && depth == 1 && !section.equals("declaration")) {
                    section = "locations";
                }
                if (depth == 0) {
                    afterProcess = false;
                }
            }
            i++;
        }
        if (template != null) {
            if (label != null) {
                labels.add(new Region(labelStart, n, new Place(template, label)));
            }
            bodies.add(new Region(bodyStart, n, new Place(template, null)));
        }
        // a template's declarations: from its body's start to its first section keyword
        for (Region body : List.copyOf(bodies)) {
            int end = firstSection(text, body.start + 1, body.end);
            labels.add(new Region(body.start + 1, end, new Place(body.place.template(), "declaration")));
        }
    }

    /** The offset of the first section keyword ({@code state}, ...) at the body's own level, or {@code end}. */
    private static int firstSection(String text, int from, int end) {
        int depth = 0;
        int i = from;
        while (i < end) {
            int skipped = afterCommentOrString(text, i);
            if (skipped != i) {
                i = skipped;
                continue;
            }
            char c = text.charAt(i);
            if (Character.isLetter(c) || c == '_') {
                int start = i;
                i = afterWord(text, i, end);
                if (depth == 0 && isSection(text.substring(start, i))) {
                    return start - 1;
                }
                continue;
            }
            if (c == '{') {
                depth++;
            } else if (c == '}') {
                depth--;
            }
            i++;
        }
        return end;
    }

    /**
     * The offset after the comment ({@code //} to the line's end, {@code /* ... *}{@code /}) or the string at {@code i},
     * or {@code i} when none starts there: the scanners skip them whole, so that their words and braces do not count.
     */
    private static int afterCommentOrString(String text, int i) {
        int n = text.length();
        if (text.startsWith("//", i)) {
            int end = text.indexOf('\n', i);
            return end < 0 ? n : end;
        }
        if (text.startsWith("/*", i)) {
            int end = text.indexOf("*/", i + 2);
            return end < 0 ? n : end + 2;
        }
        if (text.charAt(i) == '"') {
            int end = text.indexOf('"', i + 1);
            return end < 0 ? n : end + 1;
        }
        return i;
    }

    /** The offset after the identifier that starts at {@code i}, at most {@code end}. */
    private static int afterWord(String text, int i, int end) {
        while (i < end && (Character.isLetterOrDigit(text.charAt(i)) || text.charAt(i) == '_')) {
            i++;
        }
        return i;
    }

    private static boolean isSection(String word) {
        return switch (word) {
            case "state", "init", "trans", "commit", "urgent", "branchpoint" -> true;
            default -> false;
        };
    }

    private static String edgeLabel(String word) {
        return switch (word) {
            case "select" -> "select";
            case "guard" -> "guard";
            case "sync" -> "synchronisation";
            case "assign" -> "assignment";
            default -> null;
        };
    }
}
