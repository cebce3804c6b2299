package io.dtron.engine.internal.eval;

import io.dtron.model.Type;
import io.dtron.xta.Pos;

/** The values a place of an integer, boolean or scalar type may hold; booleans are stored as 0 and 1. */
final class Range {
    private final int lower;
    private final int upper;
    private final boolean bool;
    private final String text;

    private Range(int lower, int upper, boolean bool, String text) {
        this.lower = lower;
        this.upper = upper;
        this.bool = bool;
        this.text = text;
    }

    static Range of(Type type) {
        if (type instanceof Type.Int i) {
            return new Range(i.lower(), i.upper(), false, "int[" + i.lower() + "," + i.upper() + "]");
        }
        if (type instanceof Type.Bool) {
            return new Range(Integer.MIN_VALUE, Integer.MAX_VALUE, true, "bool");
        }
        if (type instanceof Type.Scalar s) {
            return new Range(0, s.size() - 1, false, s.name());
        }
        throw new IllegalArgumentException("not an integer type: " + type);
    }

    /** Whether {@code value} may be stored (every value may be stored in a boolean, as 0 or 1). */
    boolean accepts(int value) {
        return value >= lower && value <= upper;
    }

    /** The value as stored. */
    int normalize(int value) {
        return bool ? (value != 0 ? 1 : 0) : value;
    }

    /** The default value: 0, or the bound nearest to 0 of a range without 0 (as for variables). */
    int defaultValue() {
        return lower > 0 ? lower : Math.min(0, upper);
    }

    ModelRuntimeException outside(Pos pos, int value, String what) {
        return new ModelRuntimeException(pos, "the value " + value + " is outside " + text + " of " + what);
    }
}
