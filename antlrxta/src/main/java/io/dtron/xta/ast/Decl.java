package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;

/** A declaration: what can stand at the top level of a model, a template or a block. */
public sealed interface Decl {

    /** Where it was written (its name, for named declarations). */
    Pos pos();

    /** A variable, constant, clock or channel; one record per declared name. */
    record Variable(Pos pos, TypeExpr type, String name, List<ArrayDim> dims, Initializer init) implements Decl {
        public Variable {
            dims = List.copyOf(dims);
        }
    }

    /** {@code typedef type name[dims];} */
    record Typedef(Pos pos, TypeExpr type, String name, List<ArrayDim> dims) implements Decl {
        public Typedef {
            dims = List.copyOf(dims);
        }
    }

    /** A function with its body. */
    record Function(Pos pos, TypeExpr returnType, String name, List<Param> params, Stmt.Block body) implements Decl {
        public Function {
            params = List.copyOf(params);
        }
    }

    /**
     * {@code chan priority a, b < c < default;}: the levels from lowest to highest priority; a null element
     * stands for {@code default}.
     */
    record ChanPriority(Pos pos, List<List<Expr>> levels) implements Decl {
        public ChanPriority {
            levels = levels.stream().map(l -> java.util.Collections.unmodifiableList(new java.util.ArrayList<>(l)))
                    .toList();
        }
    }

    /** A template: an automaton with parameters, local declarations, locations and edges. */
    record Template(Pos pos, String name, List<Param> params, List<Decl> declarations, List<Location> locations,
                    List<String> branchpoints, String init, Pos initPos, List<Edge> edges, Coord coord)
            implements Decl {
        public Template {
            params = List.copyOf(params);
            declarations = List.copyOf(declarations);
            locations = List.copyOf(locations);
            branchpoints = List.copyOf(branchpoints);
            edges = List.copyOf(edges);
        }
    }

    /**
     * {@code P = T(args);} or the partial instantiation {@code P(params) = T(args);} ({@code :=} in old
     * syntax).
     */
    record Instantiation(Pos pos, String name, List<Param> params, String template, Pos templatePos,
                         List<Expr> args) implements Decl {
        public Instantiation {
            params = List.copyOf(params);
            args = List.copyOf(args);
        }
    }

    /**
     * {@code dynamic T(params);}: a template whose processes are created by {@code spawn} and end with
     * {@code exit()} (statistical model checking); its body is the template of the same name.
     */
    record Dynamic(Pos pos, String name, List<Param> params) implements Decl {
        public Dynamic {
            params = List.copyOf(params);
        }
    }

    /**
     * A function of an {@code import "library" { ... }} block: implemented in a native library (statistical
     * model checking). Parameters without a name have the empty name.
     *
     * @param pos        where its name was written
     * @param returnType its return type
     * @param name       the name the model calls it by
     * @param params     its parameters
     * @param library    the library's path as written
     */
    record External(Pos pos, TypeExpr returnType, String name, List<Param> params, String library) implements Decl {
        public External {
            params = List.copyOf(params);
        }
    }
}
