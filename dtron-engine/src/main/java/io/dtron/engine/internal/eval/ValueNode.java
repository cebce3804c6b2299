package io.dtron.engine.internal.eval;

import io.dtron.model.Expression;

/**
 * A compiled integer or boolean expression (booleans are 0 and 1). The subclasses here read data, compute and
 * quantify; assignments are in {@link Updates}, calls in {@link FunctionCode}.
 */
abstract class ValueNode {

    abstract int eval(Env env);

    /** A constant. */
    static final class Const extends ValueNode {
        final int value;

        Const(int value) {
            this.value = value;
        }

        @Override
        int eval(Env env) {
            return value;
        }
    }

    /** A slot of the state vector. */
    static final class VarRead extends ValueNode {
        private final int offset;

        VarRead(int offset) {
            this.offset = offset;
        }

        @Override
        int eval(Env env) {
            return env.vars[offset];
        }
    }

    /** A slot of the current frame. */
    static final class LocalRead extends ValueNode {
        private final int slot;

        LocalRead(int slot) {
            this.slot = slot;
        }

        @Override
        int eval(Env env) {
            return env.stack[env.bp + slot];
        }
    }

    /** The slot at a computed address. */
    static final class PlaceRead extends ValueNode {
        private final PlaceNode place;

        PlaceRead(PlaceNode place) {
            this.place = place;
        }

        @Override
        int eval(Env env) {
            return env.load(place.address(env));
        }
    }

    /** A slot of a function's array or struct result ({@code f().a}); the result's slots are released. */
    static final class ResultRead extends ValueNode {
        private final PlaceNode place;

        ResultRead(PlaceNode place) {
            this.place = place;
        }

        @Override
        int eval(Env env) {
            int top = env.sp;
            int value = env.load(place.address(env));
            env.sp = top;
            return value;
        }
    }

    /** An expression that is a model error whenever it is evaluated. */
    static final class Fail extends ValueNode {
        private final Expression.ModelError error;

        Fail(Expression.ModelError error) {
            this.error = error;
        }

        @Override
        int eval(Env env) {
            throw new ModelRuntimeException(error.pos(), error.message());
        }
    }

    /** An array or struct expression evaluated for its effects only (its value goes to scratch slots). */
    static final class Discard extends ValueNode {
        private final CopyNode value;
        private final int slots;

        Discard(CopyNode value, int slots) {
            this.value = value;
            this.slots = slots;
        }

        @Override
        int eval(Env env) {
            int scratch = env.reserve(slots);
            value.copyTo(env, env.varCount + scratch);
            env.sp = scratch;
            return 0;
        }
    }

    /** {@code -e}. */
    static final class Neg extends ValueNode {
        private final ValueNode operand;
        private final Expression source;

        Neg(ValueNode operand, Expression source) {
            this.operand = operand;
            this.source = source;
        }

        @Override
        int eval(Env env) {
            return Arith.neg(operand.eval(env), source);
        }
    }

    /** {@code !e}. */
    static final class Not extends ValueNode {
        private final ValueNode operand;

        Not(ValueNode operand) {
            this.operand = operand;
        }

        @Override
        int eval(Env env) {
            return operand.eval(env) == 0 ? 1 : 0;
        }
    }

    /** A binary operator: both operands evaluated left to right. */
    abstract static class Binary extends ValueNode {
        final ValueNode left;
        final ValueNode right;

        Binary(ValueNode left, ValueNode right) {
            this.left = left;
            this.right = right;
        }
    }

    /** An arithmetic operator that may fail (overflow, division by zero). */
    abstract static class Checked extends Binary {
        final Expression source;

        Checked(ValueNode left, ValueNode right, Expression source) {
            super(left, right);
            this.source = source;
        }
    }

    /** {@code +}. */
    static final class Add extends Checked {
        Add(ValueNode left, ValueNode right, Expression source) {
            super(left, right, source);
        }

        @Override
        int eval(Env env) {
            return Arith.add(left.eval(env), right.eval(env), source);
        }
    }

    /** {@code -}. */
    static final class Sub extends Checked {
        Sub(ValueNode left, ValueNode right, Expression source) {
            super(left, right, source);
        }

        @Override
        int eval(Env env) {
            return Arith.sub(left.eval(env), right.eval(env), source);
        }
    }

    /** {@code *}. */
    static final class Mul extends Checked {
        Mul(ValueNode left, ValueNode right, Expression source) {
            super(left, right, source);
        }

        @Override
        int eval(Env env) {
            return Arith.mul(left.eval(env), right.eval(env), source);
        }
    }

    /** {@code **} on integers. */
    static final class Pow extends Checked {
        Pow(ValueNode left, ValueNode right, Expression source) {
            super(left, right, source);
        }

        @Override
        int eval(Env env) {
            return Arith.pow(left.eval(env), right.eval(env), source);
        }
    }

    /** {@code /}, truncating toward zero. */
    static final class Div extends Checked {
        Div(ValueNode left, ValueNode right, Expression source) {
            super(left, right, source);
        }

        @Override
        int eval(Env env) {
            return Arith.div(left.eval(env), right.eval(env), source);
        }
    }

    /** {@code %}, with the sign of the dividend. */
    static final class Mod extends Checked {
        Mod(ValueNode left, ValueNode right, Expression source) {
            super(left, right, source);
        }

        @Override
        int eval(Env env) {
            return Arith.mod(left.eval(env), right.eval(env), source);
        }
    }

    /** {@code <<}. */
    static final class Shl extends Checked {
        Shl(ValueNode left, ValueNode right, Expression source) {
            super(left, right, source);
        }

        @Override
        int eval(Env env) {
            return Arith.shl(left.eval(env), right.eval(env), source);
        }
    }

    /** {@code >>} (arithmetic). */
    static final class Shr extends Binary {
        Shr(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) >> right.eval(env);
        }
    }

    /** {@code <?}. */
    static final class Min extends Binary {
        Min(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return Math.min(left.eval(env), right.eval(env));
        }
    }

    /** {@code >?}. */
    static final class Max extends Binary {
        Max(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return Math.max(left.eval(env), right.eval(env));
        }
    }

    /** {@code &}. */
    static final class BitAnd extends Binary {
        BitAnd(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) & right.eval(env);
        }
    }

    /** {@code |}. */
    static final class BitOr extends Binary {
        BitOr(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) | right.eval(env);
        }
    }

    /** {@code ^}. */
    static final class BitXor extends Binary {
        BitXor(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) ^ right.eval(env);
        }
    }

    /** {@code <}. */
    static final class Lt extends Binary {
        Lt(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) < right.eval(env) ? 1 : 0;
        }
    }

    /** {@code <=}. */
    static final class Le extends Binary {
        Le(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) <= right.eval(env) ? 1 : 0;
        }
    }

    /** {@code ==}. */
    static final class Eq extends Binary {
        Eq(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) == right.eval(env) ? 1 : 0;
        }
    }

    /** {@code !=}. */
    static final class Ne extends Binary {
        Ne(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) != right.eval(env) ? 1 : 0;
        }
    }

    /** {@code >=}. */
    static final class Ge extends Binary {
        Ge(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) >= right.eval(env) ? 1 : 0;
        }
    }

    /** {@code >}. */
    static final class Gt extends Binary {
        Gt(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) > right.eval(env) ? 1 : 0;
        }
    }

    /** {@code &&}, short-circuit. */
    static final class And extends Binary {
        And(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) != 0 && right.eval(env) != 0 ? 1 : 0;
        }
    }

    /** {@code ||}, short-circuit. */
    static final class Or extends Binary {
        Or(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) != 0 || right.eval(env) != 0 ? 1 : 0;
        }
    }

    /** {@code imply}, short-circuit. */
    static final class Imply extends Binary {
        Imply(ValueNode left, ValueNode right) {
            super(left, right);
        }

        @Override
        int eval(Env env) {
            return left.eval(env) == 0 || right.eval(env) != 0 ? 1 : 0;
        }
    }

    /** {@code c ? a : b}. */
    static final class Conditional extends ValueNode {
        private final ValueNode condition;
        private final ValueNode then;
        private final ValueNode otherwise;

        Conditional(ValueNode condition, ValueNode then, ValueNode otherwise) {
            this.condition = condition;
            this.then = then;
            this.otherwise = otherwise;
        }

        @Override
        int eval(Env env) {
            return condition.eval(env) != 0 ? then.eval(env) : otherwise.eval(env);
        }
    }

    /**
     * A quantifier: the body is evaluated with each value {@code lower..upper} in a frame slot; every value
     * counts as a step against endless evaluations.
     */
    abstract static class Quantifier extends ValueNode {
        final int slot;
        final long lower;
        final long upper;
        final ValueNode body;
        final Expression source;

        Quantifier(Expression.Quantified q, ValueNode body) {
            this.slot = q.slot();
            this.lower = q.lower();
            this.upper = q.upper();
            this.body = body;
            this.source = q;
        }

        /** Binds the quantified name to {@code value} and evaluates the body. */
        final int bodyAt(Env env, long value) {
            env.tick(source.pos());
            env.stack[env.bp + slot] = (int) value;
            return body.eval(env);
        }
    }

    /** {@code forall}: stops at the first false body. */
    static final class Forall extends Quantifier {
        Forall(Expression.Quantified q, ValueNode body) {
            super(q, body);
        }

        @Override
        int eval(Env env) {
            for (long v = lower; v <= upper; v++) {
                if (bodyAt(env, v) == 0) {
                    return 0;
                }
            }
            return 1;
        }
    }

    /** {@code exists}: stops at the first true body. */
    static final class Exists extends Quantifier {
        Exists(Expression.Quantified q, ValueNode body) {
            super(q, body);
        }

        @Override
        int eval(Env env) {
            for (long v = lower; v <= upper; v++) {
                if (bodyAt(env, v) != 0) {
                    return 1;
                }
            }
            return 0;
        }
    }

    /** {@code sum}. */
    static final class Sum extends Quantifier {
        Sum(Expression.Quantified q, ValueNode body) {
            super(q, body);
        }

        @Override
        int eval(Env env) {
            int sum = 0;
            for (long v = lower; v <= upper; v++) {
                sum = Arith.add(sum, bodyAt(env, v), source);
            }
            return sum;
        }
    }
}
