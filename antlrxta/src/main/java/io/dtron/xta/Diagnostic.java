package io.dtron.xta;

import java.util.Comparator;
import java.util.Objects;

/**
 * A problem found in a model: an error (the model is rejected) or a warning (it loads, but something is
 * suspicious), with the place where it was written.
 *
 * @param severity error or warning
 * @param pos      where, or null when it concerns the whole input (e.g. an unreadable file)
 * @param file     the file name (also set when {@code pos} is null)
 * @param message  what is wrong, in words for the model's author
 */
public record Diagnostic(Severity severity, Pos pos, String file, String message) {

    /** How bad a diagnostic is. */
    public enum Severity {
        /** The model is rejected. */
        ERROR,
        /** The model loads, but the user should look. */
        WARNING
    }

    /** The order in which diagnostics are reported: by file, then line and column; those about a whole file first. */
    public static final Comparator<Diagnostic> BY_POSITION = Comparator.comparing(Diagnostic::file)
            .thenComparingInt(Diagnostic::line).thenComparingInt(Diagnostic::column);

    public Diagnostic {
        Objects.requireNonNull(severity, "severity");
        Objects.requireNonNull(file, "file");
        Objects.requireNonNull(message, "message");
    }

    /** An error at {@code pos}. */
    public static Diagnostic error(Pos pos, String message) {
        return new Diagnostic(Severity.ERROR, pos, pos.fragment().file(), message);
    }

    /** A warning at {@code pos}. */
    public static Diagnostic warning(Pos pos, String message) {
        return new Diagnostic(Severity.WARNING, pos, pos.fragment().file(), message);
    }

    /** An error about a whole file. */
    public static Diagnostic fileError(String file, String message) {
        return new Diagnostic(Severity.ERROR, null, file, message);
    }

    /** Whether this is an error. */
    public boolean isError() {
        return severity == Severity.ERROR;
    }

    /** The 1-based line, or 0 when there is no position. */
    public int line() {
        return pos == null ? 0 : pos.line();
    }

    /** The 1-based column, or 0 when there is no position. */
    public int column() {
        return pos == null ? 0 : pos.column();
    }

    /** The template the problem is in, or null. */
    public String template() {
        return pos == null ? null : pos.fragment().templateAt(pos.start());
    }

    /** The kind of label or element the problem is in ({@code guard}, {@code declaration}...), or null. */
    public String labelKind() {
        return pos == null ? null : pos.fragment().kindAt(pos.start());
    }

    /**
     * One line for a terminal: {@code file:line:column: error: message (template T, guard label, column 3)}.
     */
    public String format() {
        StringBuilder sb = new StringBuilder(file);
        if (pos != null) {
            sb.append(':').append(line()).append(':').append(column());
        }
        sb.append(": ").append(severity == Severity.ERROR ? "error" : "warning").append(": ").append(message);
        if (pos != null && pos.fragment().isPart()) {
            sb.append(" (");
            if (template() != null) {
                sb.append("template ").append(template()).append(", ");
            }
            sb.append(labelKind()).append(pos.fragment().kind() != null && isLabel(labelKind()) ? " label" : "")
                    .append(", column ").append(pos.columnInFragment()).append(')');
        } else if (pos != null && template() != null) {
            // an .xta file: the file's line and column, and the template and label around them
            sb.append(" (template ").append(template());
            if (labelKind() != null) {
                sb.append(", ").append(labelKind()).append(isLabel(labelKind()) ? " label" : "");
            }
            sb.append(')');
        }
        return sb.toString();
    }

    private static boolean isLabel(String kind) {
        return switch (kind) {
            case "guard", "synchronisation", "assignment", "invariant", "select" -> true;
            default -> false;
        };
    }

    @Override
    public String toString() {
        return format();
    }
}
