package io.dtron.xta;

import java.util.List;

/**
 * What parsing produced: the value (null when the text could not be parsed at all) and every diagnostic.
 *
 * @param value       the parsed value, or null
 * @param diagnostics errors and warnings, in the order found
 * @param <T>         the kind of value
 */
public record Parsed<T>(T value, List<Diagnostic> diagnostics) {
    public Parsed {
        diagnostics = List.copyOf(diagnostics);
    }

    /** Whether any diagnostic is an error; then {@link #value()} must not be used for further stages. */
    public boolean hasErrors() {
        return diagnostics.stream().anyMatch(Diagnostic::isError);
    }
}
