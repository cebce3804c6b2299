package io.dtron.xta.ast;

import java.util.List;

/**
 * A whole model as written: declarations in scope order (global declarations, templates, then the system
 * section's declarations and instantiations), the system line and the queries.
 *
 * @param file         the file name
 * @param declarations all declarations, in the order in which they come into scope
 * @param system       the system line, or null when the model has none
 * @param queries      the queries, possibly empty
 */
public record Nta(String file, List<Decl> declarations, SystemLine system, List<Query> queries) {
    public Nta {
        declarations = List.copyOf(declarations);
        queries = List.copyOf(queries);
    }

    /** The templates among the declarations. */
    public List<Decl.Template> templates() {
        return declarations.stream().filter(d -> d instanceof Decl.Template).map(d -> (Decl.Template) d).toList();
    }
}
