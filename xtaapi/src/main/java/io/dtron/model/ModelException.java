package io.dtron.model;

import io.dtron.xta.Diagnostic;
import java.util.List;
import java.util.stream.Collectors;

/**
 * A model (or interface file) that cannot be used: it carries every error found, each with its file, line
 * and column. The message is the list of formatted diagnostics, ready for a terminal.
 */
public final class ModelException extends Exception {
    private static final long serialVersionUID = 1L;

    private final transient List<Diagnostic> diagnostics;

    /** An exception for these diagnostics (errors, possibly with warnings). */
    public ModelException(List<Diagnostic> diagnostics) {
        super(diagnostics.stream().map(Diagnostic::format).collect(Collectors.joining("\n")));
        this.diagnostics = List.copyOf(diagnostics);
    }

    /** Every diagnostic, errors and warnings, in the order found. */
    public List<Diagnostic> diagnostics() {
        return diagnostics;
    }

    /** The errors only. */
    public List<Diagnostic> errors() {
        return diagnostics.stream().filter(Diagnostic::isError).toList();
    }
}
