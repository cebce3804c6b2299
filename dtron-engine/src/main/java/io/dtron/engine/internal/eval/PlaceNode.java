package io.dtron.engine.internal.eval;

import io.dtron.model.Expression;

/**
 * A compiled lvalue: computes the address of integer data (see {@link Env} for the address space), or the
 * number of a clock or a channel. Indices are checked against the array's index range.
 */
abstract class PlaceNode {

    abstract int address(Env env);

    /** An address known when compiling: a variable, a constant table, a clock, a channel. */
    static final class Fixed extends PlaceNode {
        final int address;

        Fixed(int address) {
            this.address = address;
        }

        @Override
        int address(Env env) {
            return address;
        }
    }

    /** A slot of the current frame. */
    static final class Local extends PlaceNode {
        private final int slot;

        Local(int slot) {
            this.slot = slot;
        }

        @Override
        int address(Env env) {
            return env.varCount + env.bp + slot;
        }
    }

    /** What a reference parameter refers to: the address its slot holds. */
    static final class Ref extends PlaceNode {
        private final int slot;

        Ref(int slot) {
            this.slot = slot;
        }

        @Override
        int address(Env env) {
            return env.stack[env.bp + slot];
        }
    }

    /** A part at a fixed offset: a struct field, or an array element at a constant index. */
    static final class Offset extends PlaceNode {
        private final PlaceNode base;
        private final int offset;

        Offset(PlaceNode base, int offset) {
            this.base = base;
            this.offset = offset;
        }

        @Override
        int address(Env env) {
            return base.address(env) + offset;
        }
    }

    /** An array element at a computed index. */
    static final class Index extends PlaceNode {
        private final PlaceNode array;
        private final ValueNode index;
        private final int first;
        private final int last;
        private final int elementSize;
        private final Expression.Index source;

        Index(PlaceNode array, ValueNode index, int first, int length, int elementSize, Expression.Index source) {
            this.array = array;
            this.index = index;
            this.first = first;
            this.last = first + length - 1;
            this.elementSize = elementSize;
            this.source = source;
        }

        @Override
        int address(Env env) {
            int base = array.address(env);
            int i = index.eval(env);
            if (i < first || i > last) {
                throw new ModelRuntimeException(source.pos(), "index " + i + " is out of range [" + first + ","
                        + last + "] of '" + source.array().pos().text() + "'");
            }
            return base + (i - first) * elementSize;
        }
    }

    /**
     * The array or struct a function returns, in slots taken above the stack top; whoever reads through this
     * place releases them afterwards ({@link ValueNode.ResultRead}, {@link CopyNode.FromPlace}).
     */
    static final class Result extends PlaceNode {
        private final CopyNode call;
        private final int slots;

        Result(CopyNode call, int slots) {
            this.call = call;
            this.slots = slots;
        }

        @Override
        int address(Env env) {
            int result = env.varCount + env.reserve(slots);
            call.copyTo(env, result);
            return result;
        }
    }

    /** An lvalue that is a model error whenever it is evaluated. */
    static final class Fail extends PlaceNode {
        private final Expression.ModelError error;

        Fail(Expression.ModelError error) {
            this.error = error;
        }

        @Override
        int address(Env env) {
            throw new ModelRuntimeException(error.pos(), error.message());
        }
    }
}
