package io.dtron.engine.internal.eval;

import io.dtron.model.Expression;

/**
 * A compiled array or struct value: copies its slots to an address (function arguments by value, local
 * initialisers, whole assignments, returns).
 */
abstract class CopyNode {

    abstract void copyTo(Env env, int destination);

    /**
     * The value stored at a place: a variable, a local, a constant table, a function's result, or an element or
     * field of one. Stack slots taken by a function's result are released.
     */
    static final class FromPlace extends CopyNode {
        private final PlaceNode place;
        private final int slots;

        FromPlace(PlaceNode place, int slots) {
            this.place = place;
            this.slots = slots;
        }

        @Override
        void copyTo(Env env, int destination) {
            int top = env.sp;
            env.copy(place.address(env), destination, slots);
            env.sp = top;
        }
    }

    /** A value that is a model error whenever it is evaluated. */
    static final class Fail extends CopyNode {
        private final Expression.ModelError error;

        Fail(Expression.ModelError error) {
            this.error = error;
        }

        @Override
        void copyTo(Env env, int destination) {
            throw new ModelRuntimeException(error.pos(), error.message());
        }
    }
}
