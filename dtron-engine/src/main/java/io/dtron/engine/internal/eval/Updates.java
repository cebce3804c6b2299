package io.dtron.engine.internal.eval;

import io.dtron.model.Expression;
import io.dtron.model.Expression.Operator;

/**
 * Compiled assignments and increments. Integer stores are checked against the target's range (booleans are
 * stored as 0 and 1); clock assignments are reported to the evaluation's {@link ClockResets}.
 */
final class Updates {
    private Updates() {
    }

    /** Stores {@code value} at {@code address} after checking it against the range of {@code target}. */
    static int store(Env env, int address, int value, Range range, Expression target, Expression at) {
        if (!range.accepts(value)) {
            throw range.outside(at.pos(), value, "'" + env.describe(address, target) + "'");
        }
        int stored = range.normalize(value);
        env.store(address, stored);
        return stored;
    }

    /** {@code target = value} on integer data. */
    static final class Assign extends ValueNode {
        private final PlaceNode target;
        private final ValueNode value;
        private final Range range;
        private final Expression.Assign source;

        Assign(PlaceNode target, ValueNode value, Range range, Expression.Assign source) {
            this.target = target;
            this.value = value;
            this.range = range;
            this.source = source;
        }

        @Override
        int eval(Env env) {
            int address = target.address(env);
            return store(env, address, value.eval(env), range, source.target(), source);
        }
    }

    /** {@code target op= value}. */
    static final class Compound extends ValueNode {
        private final PlaceNode target;
        private final Operator op;
        private final ValueNode value;
        private final Range range;
        private final Expression.Assign source;

        Compound(PlaceNode target, ValueNode value, Range range, Expression.Assign source) {
            this.target = target;
            this.op = source.op();
            this.value = value;
            this.range = range;
            this.source = source;
        }

        @Override
        int eval(Env env) {
            int address = target.address(env);
            int old = env.load(address);
            int result = Arith.apply(op, old, value.eval(env), source);
            return store(env, address, result, range, source.target(), source);
        }
    }

    /** {@code ++x}, {@code x++}, {@code --x}, {@code x--}. */
    static final class Increment extends ValueNode {
        private final PlaceNode target;
        private final Range range;
        private final Expression.Increment source;

        Increment(PlaceNode target, Range range, Expression.Increment source) {
            this.target = target;
            this.range = range;
            this.source = source;
        }

        @Override
        int eval(Env env) {
            int address = target.address(env);
            int old = env.load(address);
            int updated = store(env, address, Arith.add(old, source.delta(), source), range, source.target(), source);
            return source.prefix() ? updated : old;
        }
    }

    /** {@code x = value} on a clock: reported as a reset. */
    static final class ClockAssign extends ValueNode {
        private final PlaceNode clock;
        private final ValueNode value;
        private final Expression.Assign source;

        ClockAssign(PlaceNode clock, ValueNode value, Expression.Assign source) {
            this.clock = clock;
            this.value = value;
            this.source = source;
        }

        @Override
        int eval(Env env) {
            int x = clock.address(env);
            int v = value.eval(env);
            if (v < 0) {
                throw new ModelRuntimeException(source.pos(), "a clock cannot be set to a negative value: '"
                        + source.pos().text() + "' gives " + v);
            }
            if (env.resets == null) {
                throw new IllegalArgumentException("'" + source.pos().text() + "' assigns a clock: use execute()");
            }
            env.resets.add(x, v, source.pos());
            return v;
        }
    }

    /** {@code target = value} on a whole array or struct. */
    static final class AssignAll extends ValueNode {
        private final PlaceNode target;
        private final CopyNode value;

        AssignAll(PlaceNode target, CopyNode value) {
            this.target = target;
            this.value = value;
        }

        /** Performs the assignment; returns the target's address. */
        int perform(Env env) {
            int address = target.address(env);
            value.copyTo(env, address);
            return address;
        }

        @Override
        int eval(Env env) {
            perform(env);
            return 0;
        }
    }

    /** The value of a whole-array or whole-struct assignment used as a value: {@code a = (b = c)}. */
    static final class AssignAllValue extends CopyNode {
        private final AssignAll assign;
        private final int slots;

        AssignAllValue(AssignAll assign, int slots) {
            this.assign = assign;
            this.slots = slots;
        }

        @Override
        void copyTo(Env env, int destination) {
            env.copy(assign.perform(env), destination, slots);
        }
    }
}
