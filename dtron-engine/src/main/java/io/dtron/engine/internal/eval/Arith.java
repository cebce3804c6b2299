package io.dtron.engine.internal.eval;

import io.dtron.model.Expression;
import io.dtron.model.Expression.Operator;

/**
 * Integer arithmetic with the model's semantics: 32-bit values, {@code /} and {@code %} truncate toward zero,
 * overflow and division by zero are model errors (the same rules as constant folding at load time).
 */
final class Arith {
    private Arith() {
    }

    static int add(int x, int y, Expression at) {
        int r = x + y;
        if (((x ^ r) & (y ^ r)) < 0) {
            throw overflow(at);
        }
        return r;
    }

    static int sub(int x, int y, Expression at) {
        int r = x - y;
        if (((x ^ y) & (x ^ r)) < 0) {
            throw overflow(at);
        }
        return r;
    }

    static int mul(int x, int y, Expression at) {
        long r = (long) x * y;
        if ((int) r != r) {
            throw overflow(at);
        }
        return (int) r;
    }

    /** {@code x ** y}; a negative exponent is a model error, as an overflow is. */
    static int pow(int x, int y, Expression at) {
        if (y < 0) {
            throw new ModelRuntimeException(at.pos(), "negative exponent in '" + at.pos().text() + "'");
        }
        if (x == 0 || x == 1) {
            return y == 0 ? 1 : x;
        }
        if (x == -1) {
            return y % 2 == 0 ? 1 : -1;
        }
        long r = 1;
        for (int i = 0; i < y; i++) {
            // |x| >= 2: an overflow comes within 32 steps
            r *= x;
            if ((int) r != r) {
                throw overflow(at);
            }
        }
        return (int) r;
    }

    static int div(int x, int y, Expression at) {
        if (y == 0) {
            throw divisionByZero(at);
        }
        if (x == Integer.MIN_VALUE && y == -1) {
            throw overflow(at);
        }
        return x / y;
    }

    static int mod(int x, int y, Expression at) {
        if (y == 0) {
            throw divisionByZero(at);
        }
        return x % y;
    }

    static int shl(int x, int y, Expression at) {
        long r = (long) x << y;
        if ((int) r != r) {
            throw overflow(at);
        }
        return (int) r;
    }

    static int neg(int x, Expression at) {
        if (x == Integer.MIN_VALUE) {
            throw overflow(at);
        }
        return -x;
    }

    /** {@code x op y} for the operators of compound assignments. */
    static int apply(Operator op, int x, int y, Expression at) {
        return switch (op) {
            case ADD -> add(x, y, at);
            case SUB -> sub(x, y, at);
            case MUL -> mul(x, y, at);
            case DIV -> div(x, y, at);
            case MOD -> mod(x, y, at);
            case SHL -> shl(x, y, at);
            case SHR -> x >> y;
            case MIN -> Math.min(x, y);
            case MAX -> Math.max(x, y);
            case BIT_AND -> x & y;
            case BIT_OR -> x | y;
            case BIT_XOR -> x ^ y;
            default -> throw new IllegalArgumentException("not an arithmetic operator: " + op);
        };
    }

    static ModelRuntimeException overflow(Expression at) {
        return new ModelRuntimeException(at.pos(), "integer overflow in '" + at.pos().text() + "'");
    }

    private static ModelRuntimeException divisionByZero(Expression at) {
        return new ModelRuntimeException(at.pos(), "division by zero in '" + at.pos().text() + "'");
    }
}
