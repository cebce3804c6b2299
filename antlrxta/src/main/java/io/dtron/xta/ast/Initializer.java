package io.dtron.xta.ast;

import io.dtron.xta.Pos;

/** The initial value of a variable: an expression or a brace list for arrays and structs. */
public sealed interface Initializer {

    /** Where it was written. */
    Pos pos();

    /** A single expression. */
    record Single(Pos pos, Expr value) implements Initializer {
    }

    /** {@code { a, b, ... }}. */
    record Braces(Pos pos, java.util.List<Initializer> elements) implements Initializer {
        public Braces {
            elements = java.util.List.copyOf(elements);
        }
    }
}
