package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;

/** A statement of a function body. */
public sealed interface Stmt {

    /** Where it was written. */
    Pos pos();

    /** {@code { declarations statements }} */
    record Block(Pos pos, List<Decl> declarations, List<Stmt> statements) implements Stmt {
        public Block {
            declarations = List.copyOf(declarations);
            statements = List.copyOf(statements);
        }
    }

    /** {@code ;} */
    record Empty(Pos pos) implements Stmt {
    }

    /** {@code expression;} */
    record ExprStmt(Pos pos, Expr expr) implements Stmt {
    }

    /** {@code for (init; condition; step) body}; the condition may be null. */
    record For(Pos pos, List<Expr> init, Expr condition, List<Expr> step, Stmt body) implements Stmt {
        public For {
            init = List.copyOf(init);
            step = List.copyOf(step);
        }
    }

    /** {@code for (name : type) body} */
    record Iteration(Pos pos, String name, TypeExpr type, Stmt body) implements Stmt {
    }

    /** {@code while (condition) body} */
    record While(Pos pos, Expr condition, Stmt body) implements Stmt {
    }

    /** {@code do body while (condition);} */
    record DoWhile(Pos pos, Stmt body, Expr condition) implements Stmt {
    }

    /** {@code if (condition) then else otherwise}; {@code otherwise} may be null. */
    record If(Pos pos, Expr condition, Stmt then, Stmt otherwise) implements Stmt {
    }

    /** {@code return value;}; the value may be null. */
    record Return(Pos pos, Expr value) implements Stmt {
    }

    /** {@code break;} */
    record Break(Pos pos) implements Stmt {
    }

    /** {@code continue;} */
    record Continue(Pos pos) implements Stmt {
    }

    /** {@code assert condition;} */
    record Assert(Pos pos, Expr condition) implements Stmt {
    }
}
