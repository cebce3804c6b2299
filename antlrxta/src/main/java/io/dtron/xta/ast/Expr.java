package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;

/** An expression as written in the model. */
public sealed interface Expr {

    /** Where it was written. */
    Pos pos();

    /** An integer literal. */
    record IntLit(Pos pos, long value) implements Expr {
    }

    /** A floating-point literal. */
    record DoubleLit(Pos pos, double value) implements Expr {
    }

    /** A string literal (without its quotes), an argument of an external function: {@code log("start")}. */
    record StringLit(Pos pos, String value) implements Expr {
    }

    /** {@code true} or {@code false}. */
    record BoolLit(Pos pos, boolean value) implements Expr {
    }

    /** {@code deadlock} in a query. */
    record Deadlock(Pos pos) implements Expr {
    }

    /** A name. */
    record Ident(Pos pos, String name) implements Expr {
    }

    /** {@code array[index]} */
    record Index(Pos pos, Expr array, Expr index) implements Expr {
    }

    /** {@code value.name}: a struct field, or a process's location in a query. */
    record Field(Pos pos, Expr value, String name) implements Expr {
    }

    /** {@code function(args)} */
    record Call(Pos pos, Expr function, List<Expr> args) implements Expr {
        public Call {
            args = List.copyOf(args);
        }
    }

    /** A unary operator applied to an operand. */
    record Unary(Pos pos, UnaryOp op, Expr operand) implements Expr {
    }

    /** A binary operator. */
    record Binary(Pos pos, BinaryOp op, Expr left, Expr right) implements Expr {
    }

    /** An assignment; {@code op} is null for plain {@code =} (or {@code :=}). */
    record Assign(Pos pos, BinaryOp op, Expr target, Expr value) implements Expr {
    }

    /** {@code condition ? then : otherwise} */
    record Conditional(Pos pos, Expr condition, Expr then, Expr otherwise) implements Expr {
    }

    /** {@code spawn T(args)}: creates a process of the dynamic template {@code T} (statistical model checking). */
    record Spawn(Pos pos, String template, Pos templatePos, List<Expr> args) implements Expr {
        public Spawn {
            args = List.copyOf(args);
        }
    }

    /** {@code forall (name : type) body}, {@code exists (...)} or {@code sum (...)}. */
    record Quantifier(Pos pos, QuantifierKind kind, String name, TypeExpr type, Expr body) implements Expr {
    }

    /** Unary operators. */
    enum UnaryOp {
        NEG("-"), PLUS("+"), NOT("!"), PRE_INC("++"), PRE_DEC("--"), POST_INC("++"), POST_DEC("--"),
        /** {@code x'}: the rate of a clock, in invariants of stopwatch models. */
        PRIME("'");

        private final String symbol;

        UnaryOp(String symbol) {
            this.symbol = symbol;
        }

        /** The operator as written. */
        public String symbol() {
            return symbol;
        }
    }

    /** Binary operators ({@code and}, {@code or} and {@code imply} are the keyword forms). */
    enum BinaryOp {
        POW("**"), MUL("*"), DIV("/"), MOD("%"), ADD("+"), SUB("-"), SHL("<<"), SHR(">>"), MIN("<?"), MAX(">?"),
        LT("<"), LE("<="), GE(">="), GT(">"), EQ("=="), NE("!="), BIT_AND("&"), BIT_XOR("^"), BIT_OR("|"),
        AND("&&"), OR("||"), IMPLY("imply");

        private final String symbol;

        BinaryOp(String symbol) {
            this.symbol = symbol;
        }

        /** The operator as written. */
        public String symbol() {
            return symbol;
        }

        /** Whether this compares two values. */
        public boolean isComparison() {
            return this == LT || this == LE || this == GE || this == GT || this == EQ || this == NE;
        }
    }

    /** The three quantifiers. */
    enum QuantifierKind { FORALL, EXISTS, SUM }
}
