package io.dtron.model;

import io.dtron.xta.Pos;
import java.util.List;

/** A resolved statement of a function body. */
public sealed interface Statement {

    /** Where it was written. */
    Pos pos();

    /** Statements in order. */
    record Block(Pos pos, List<Statement> statements) implements Statement {
        public Block {
            statements = List.copyOf(statements);
        }
    }

    /** An expression evaluated for its effect. */
    record Eval(Pos pos, Expression expression) implements Statement {
    }

    /**
     * Initialises a local variable's slots: from an expression, or, when it is null, to the default values
     * (0, or the bound nearest 0 of a range that excludes 0, as for variables).
     */
    record InitLocal(Pos pos, int slot, Type type, Expression initial) implements Statement {
    }

    /** {@code if}; {@code otherwise} may be null. */
    record If(Pos pos, Expression condition, Statement then, Statement otherwise) implements Statement {
    }

    /** {@code while}. */
    record While(Pos pos, Expression condition, Statement body) implements Statement {
    }

    /** {@code do ... while}. */
    record DoWhile(Pos pos, Statement body, Expression condition) implements Statement {
    }

    /** {@code for (init; condition; step)}; a null condition is true. */
    record For(Pos pos, List<Expression> init, Expression condition, List<Expression> step, Statement body)
            implements Statement {
        public For {
            init = List.copyOf(init);
            step = List.copyOf(step);
        }
    }

    /** {@code for (i : T)}: {@code slot} takes the values {@code lower..upper}. */
    record Iterate(Pos pos, int slot, int lower, int upper, Statement body) implements Statement {
    }

    /** {@code return}; the value is null in void functions. */
    record Return(Pos pos, Expression value) implements Statement {
    }

    /** {@code break}. */
    record Break(Pos pos) implements Statement {
    }

    /** {@code continue}. */
    record Continue(Pos pos) implements Statement {
    }

    /** {@code assert}: a model error when false. */
    record Assert(Pos pos, Expression condition) implements Statement {
    }
}
