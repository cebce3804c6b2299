package io.dtron.model.internal;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Pos;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Set;

/**
 * The diagnostics of one load. A template compiled once per process reports each problem once: duplicates
 * (same place, same message) are dropped.
 */
final class Diagnostics {
    private final List<Diagnostic> all = new ArrayList<>();
    private final Set<String> seen = new HashSet<>();

    void error(Pos pos, String message) {
        add(Diagnostic.error(pos, message));
    }

    void warning(Pos pos, String message) {
        add(Diagnostic.warning(pos, message));
    }

    void add(Diagnostic d) {
        String key = (d.pos() == null ? d.file() : d.pos().fragment().toString() + "@"
                + System.identityHashCode(d.pos().fragment()) + ":" + d.pos().start()) + "|" + d.message();
        if (seen.add(key)) {
            all.add(d);
        }
    }

    boolean hasErrors() {
        return all.stream().anyMatch(Diagnostic::isError);
    }

    List<Diagnostic> all() {
        return all;
    }
}
