package io.dtron.model;

import io.dtron.xta.Pos;
import java.util.List;

/**
 * A resolved, type-checked expression of the network: names are bound to variables, clocks, channels and
 * frame slots; constants are folded. The engine evaluates these trees directly, without reparsing.
 */
public sealed interface Expression {

    /** Where the expression was written (for errors at run time). */
    Pos pos();

    /** The expression's type. */
    Type type();

    /** Whether the expression is a folded constant. */
    default boolean isConstant() {
        return this instanceof Constant;
    }

    /** An integer or boolean value known at load time. */
    record Constant(Pos pos, Type type, int value) implements Expression {
    }

    /** A {@code double} literal (statistical model checking; the engine does not evaluate it). */
    record DoubleConstant(Pos pos, Type type, double value) implements Expression {
    }

    /** A string literal, passed to an external function (statistical model checking; never evaluated). */
    record StringConstant(Pos pos, Type type, String value) implements Expression {
    }

    /** A constant array or struct known at load time, laid out like a variable of its type. */
    record ConstantTable(Pos pos, Type type, int[] values) implements Expression {
        public ConstantTable {
            values = values.clone();
        }

        /** The values (a copy). */
        @Override
        public int[] values() {
            return values.clone();
        }

        /** One value without copying. */
        public int value(int slot) {
            return values[slot];
        }
    }

    /** A whole variable of the integer state vector. */
    record VariableRef(Pos pos, Type type, Variable variable) implements Expression {
    }

    /** A whole clock or clock array. */
    record ClockRef(Pos pos, Type type, ClockVariable clock) implements Expression {
    }

    /** A whole channel or channel array. */
    record ChannelRef(Pos pos, Type type, ChannelVariable channel) implements Expression {
    }

    /**
     * A slot of the current frame: a function's parameter or local variable, a select binding of an edge or
     * a quantifier's bound name. A reference slot holds the location of what it refers to.
     */
    record LocalRef(Pos pos, Type type, int slot, String name, boolean reference) implements Expression {
    }

    /** {@code array[index]}; the index is checked against the array's index type when evaluated. */
    record Index(Pos pos, Type type, Expression array, Expression index) implements Expression {
    }

    /** {@code struct.field}. */
    record FieldRef(Pos pos, Type type, Expression struct, int field) implements Expression {
    }

    /** A unary operator: {@code -e} or {@code !e}. */
    record Unary(Pos pos, Type type, Operator op, Expression operand) implements Expression {
    }

    /** A binary operator; for clocks, a comparison is a clock constraint. */
    record Binary(Pos pos, Type type, Operator op, Expression left, Expression right) implements Expression {
    }

    /** {@code condition ? then : otherwise}. */
    record Conditional(Pos pos, Type type, Expression condition, Expression then, Expression otherwise)
            implements Expression {
    }

    /** {@code target = value} or a compound assignment ({@code op} is then the arithmetic operator). */
    record Assign(Pos pos, Type type, Expression target, Operator op, Expression value) implements Expression {
    }

    /** {@code ++x}, {@code x++}, {@code --x}, {@code x--}. */
    record Increment(Pos pos, Type type, Expression target, boolean prefix, int delta) implements Expression {
    }

    /** A call of the user function number {@code function} of {@link Network#functions()}. */
    record Call(Pos pos, Type type, int function, String name, List<Expression> args) implements Expression {
        public Call {
            args = List.copyOf(args);
        }
    }

    /**
     * A call of one of Uppaal's built-in functions of statistical model checking ({@code random}, {@code fint},
     * {@code sqrt}, ...), of {@code spawn}, {@code exit} or {@code numOf} (dynamic templates), or of an external
     * function of an {@code import} block. The engine evaluates none of them: a network with one has a start
     * error.
     *
     * @param name the function's name ({@code spawn T} for a spawn of template T)
     */
    record Builtin(Pos pos, Type type, String name, List<Expression> args) implements Expression {
        public Builtin {
            args = List.copyOf(args);
        }
    }

    /**
     * {@code forall}, {@code exists} or {@code sum} over the values {@code lower..upper} bound to
     * {@code slot}.
     */
    record Quantified(Pos pos, Type type, Quantifier quantifier, int slot, int lower, int upper, Expression body)
            implements Expression {
    }

    /** {@code x' == rate} in an invariant: the rate of a clock (0 stops it). */
    record ClockRate(Pos pos, Type type, Expression clock, Expression rate) implements Expression {
    }

    /**
     * An expression that is a model error whenever it is evaluated, e.g. an argument that indexes a constant
     * array out of its bounds in one of the processes the system line expands.
     */
    record ModelError(Pos pos, Type type, String message) implements Expression {
    }

    /** Operators of the intermediate representation. */
    enum Operator {
        NEG, NOT, POW, ADD, SUB, MUL, DIV, MOD, SHL, SHR, MIN, MAX, BIT_AND, BIT_OR, BIT_XOR,
        LT, LE, EQ, NE, GE, GT, AND, OR, IMPLY
    }

    /** Quantifiers. */
    enum Quantifier { FORALL, EXISTS, SUM }
}
