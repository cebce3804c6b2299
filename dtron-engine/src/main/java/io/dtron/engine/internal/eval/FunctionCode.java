package io.dtron.engine.internal.eval;

import io.dtron.model.Function;
import io.dtron.model.Type;
import io.dtron.xta.Pos;

/**
 * A compiled user function, and the nodes that call it. A call reserves the callee's frame on the stack,
 * binds the arguments (evaluated in the caller's frame), runs the body with the frame as current and
 * releases it.
 */
final class FunctionCode {
    final Function function;
    private final boolean returnsValue;
    /** The body; set once compiled (after this object exists, so that recursive calls can refer to it). */
    StatementNode body;

    FunctionCode(Function function) {
        this.function = function;
        this.returnsValue = !(function.returnType() instanceof Type.Void);
    }

    /** Runs the body in the frame at stack index {@code frame}; returns the integer result (0 if none). */
    int invoke(Env env, int frame, Pos at) {
        env.tick(at);
        env.callee = function;
        if (++env.depth > Env.MAX_DEPTH) {
            throw env.tooDeep();
        }
        int callerBp = env.bp;
        env.bp = frame;
        int status = body.exec(env);
        env.bp = callerBp;
        env.depth--;
        if (!returnsValue) {
            return 0;
        }
        if (status != Env.RETURN) {
            throw new ModelRuntimeException(function.pos(), "function '" + function.name()
                    + "' ended without returning a value");
        }
        return env.ret;
    }

    /** Binds one argument into the callee's frame. */
    abstract static class Arg {
        final int slot;

        Arg(int slot) {
            this.slot = slot;
        }

        abstract void bind(Env env, int frame);
    }

    /** An integer, boolean or scalar by value, checked against the parameter's type. */
    static final class ValueArg extends Arg {
        private final ValueNode value;
        private final Range range;
        private final String name;
        private final Pos pos;

        ValueArg(int slot, ValueNode value, Range range, String name, Pos pos) {
            super(slot);
            this.value = value;
            this.range = range;
            this.name = name;
            this.pos = pos;
        }

        @Override
        void bind(Env env, int frame) {
            int v = value.eval(env);
            if (!range.accepts(v)) {
                throw range.outside(pos, v, "parameter '" + name + "'");
            }
            env.stack[frame + slot] = range.normalize(v);
        }
    }

    /** An array or struct by value: its slots are copied. */
    static final class CopyArg extends Arg {
        private final CopyNode value;

        CopyArg(int slot, CopyNode value) {
            super(slot);
            this.value = value;
        }

        @Override
        void bind(Env env, int frame) {
            value.copyTo(env, env.varCount + frame + slot);
        }
    }

    /** A reference: the slot holds the argument's address (or clock or channel number). */
    static final class RefArg extends Arg {
        private final PlaceNode place;

        RefArg(int slot, PlaceNode place) {
            super(slot);
            this.place = place;
        }

        @Override
        void bind(Env env, int frame) {
            int address = place.address(env);
            env.stack[frame + slot] = address;
        }
    }

    /** A call whose result is an integer, boolean or scalar (or nothing: void gives 0). */
    static final class Call extends ValueNode {
        private final FunctionCode code;
        private final Arg[] args;
        private final Pos pos;

        Call(FunctionCode code, Arg[] args, Pos pos) {
            this.code = code;
            this.args = args;
            this.pos = pos;
        }

        @Override
        int eval(Env env) {
            int frame = env.reserve(code.function.frameSize());
            for (Arg a : args) {
                a.bind(env, frame);
            }
            int result = code.invoke(env, frame, pos);
            env.sp = frame;
            return result;
        }
    }

    /** A call whose result is an array or struct: the callee returns it into slots below its frame. */
    static final class CallCopy extends CopyNode {
        private final FunctionCode code;
        private final Arg[] args;
        private final Pos pos;
        private final int slots;

        CallCopy(FunctionCode code, Arg[] args, Pos pos) {
            this.code = code;
            this.args = args;
            this.pos = pos;
            this.slots = code.function.returnType().slots();
        }

        @Override
        void copyTo(Env env, int destination) {
            int result = env.reserve(slots);
            int frame = env.reserve(code.function.frameSize());
            for (Arg a : args) {
                a.bind(env, frame);
            }
            int callerRetAddr = env.retAddr;
            env.retAddr = env.varCount + result;
            code.invoke(env, frame, pos);
            env.retAddr = callerRetAddr;
            env.copy(env.varCount + result, destination, slots);
            env.sp = result;
        }
    }
}
