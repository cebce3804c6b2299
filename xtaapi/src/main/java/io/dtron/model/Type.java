package io.dtron.model;

import java.util.List;

/**
 * The type of a declaration or an expression after resolution. Integers, booleans, scalars, arrays and
 * structs of them live in the network's integer state vector; clocks and channels have spaces of their own.
 */
public sealed interface Type {

    /** The smallest and largest value of a plain {@code int}. */
    int DEFAULT_INT_MIN = -32768;
    /** The largest value of a plain {@code int}. */
    int DEFAULT_INT_MAX = 32767;

    /** How many integer slots a value of this type takes (0 for clocks and channels). */
    int slots();

    /** How many clocks a value of this type takes. */
    default int clocks() {
        return 0;
    }

    /** How many channels a value of this type takes. */
    default int channels() {
        return 0;
    }

    /** Whether values of this type are integers, booleans or scalars (one slot, compared as numbers). */
    default boolean isIntegral() {
        return false;
    }

    /** {@code int[lower, upper]}. */
    record Int(int lower, int upper) implements Type {
        /** The plain {@code int}. */
        public static final Int DEFAULT = new Int(DEFAULT_INT_MIN, DEFAULT_INT_MAX);
        /** The type of arithmetic results, before they are assigned. */
        public static final Int UNBOUNDED = new Int(Integer.MIN_VALUE, Integer.MAX_VALUE);

        @Override
        public int slots() {
            return 1;
        }

        @Override
        public boolean isIntegral() {
            return true;
        }

        @Override
        public String toString() {
            return equals(DEFAULT) || equals(UNBOUNDED) ? "int" : "int[" + lower + "," + upper + "]";
        }
    }

    /** {@code bool}, held as 0 or 1. */
    record Bool() implements Type {
        /** The one boolean type. */
        public static final Bool INSTANCE = new Bool();

        @Override
        public int slots() {
            return 1;
        }

        @Override
        public boolean isIntegral() {
            return true;
        }

        @Override
        public String toString() {
            return "bool";
        }
    }

    /**
     * {@code scalar[size]}: a set of {@code size} symmetric values, held as 0..size-1; two scalar sets
     * declared apart are different types even when their sizes agree.
     *
     * @param size the number of values
     * @param id   a number unique to the declaration
     * @param name the typedef name, or {@code scalar[size]}
     */
    record Scalar(int size, int id, String name) implements Type {
        @Override
        public int slots() {
            return 1;
        }

        @Override
        public boolean isIntegral() {
            return true;
        }

        @Override
        public String toString() {
            return name;
        }
    }

    /**
     * {@code double}, of statistical model checking. Type-checked like Uppaal does, but DTRON's engine does not
     * compute with real numbers: a network with doubles has a start error, and the slot a double takes in the
     * state vector holds nothing.
     */
    record Double() implements Type {
        /** The one double type. */
        public static final Double INSTANCE = new Double();

        @Override
        public int slots() {
            return 1;
        }

        @Override
        public String toString() {
            return "double";
        }
    }

    /**
     * {@code string}: the type of string literals and of the parameters of external functions that take one
     * ({@code import "lib.so" { void log(const string& s); };}). Holds nothing in the state vector.
     */
    record Str() implements Type {
        /** The one string type. */
        public static final Str INSTANCE = new Str();

        @Override
        public int slots() {
            return 0;
        }

        @Override
        public String toString() {
            return "string";
        }
    }

    /** {@code clock}. */
    record Clock() implements Type {
        /** The one clock type. */
        public static final Clock INSTANCE = new Clock();

        @Override
        public int slots() {
            return 0;
        }

        @Override
        public int clocks() {
            return 1;
        }

        @Override
        public String toString() {
            return "clock";
        }
    }

    /**
     * The difference of two clocks, {@code x - y}, possibly offset by an integer, as compared in guards. (A
     * clock offset by an integer, {@code x + 2}, has type {@link Clock}.)
     */
    record ClockDifference() implements Type {
        /** The one clock-difference type. */
        public static final ClockDifference INSTANCE = new ClockDifference();

        @Override
        public int slots() {
            return 0;
        }

        @Override
        public String toString() {
            return "clock difference";
        }
    }

    /** {@code chan}, possibly {@code urgent} and/or {@code broadcast}. */
    record Channel(boolean urgent, boolean broadcast) implements Type {
        @Override
        public int slots() {
            return 0;
        }

        @Override
        public int channels() {
            return 1;
        }

        @Override
        public String toString() {
            return (urgent ? "urgent " : "") + (broadcast ? "broadcast " : "") + "chan";
        }
    }

    /**
     * An array whose valid indices are the values of {@code index}: {@code [n]} is indexed by
     * {@code int[0,n-1]}, {@code [T]} by the range or scalar set T.
     */
    record Array(Type element, Type index) implements Type {
        /** The number of elements. */
        public int length() {
            if (index instanceof Int i) {
                return i.upper() - i.lower() + 1;
            }
            return ((Scalar) index).size();
        }

        /** The smallest valid index. */
        public int firstIndex() {
            return index instanceof Int i ? i.lower() : 0;
        }

        @Override
        public int slots() {
            return length() * element.slots();
        }

        @Override
        public int clocks() {
            return length() * element.clocks();
        }

        @Override
        public int channels() {
            return length() * element.channels();
        }

        @Override
        public String toString() {
            return element + "[" + (index instanceof Int i && i.lower() == 0 ? String.valueOf(length()) : index) + "]";
        }
    }

    /** A struct; its fields are laid out one after the other. */
    record Struct(List<Field> fields) implements Type {
        public Struct {
            fields = List.copyOf(fields);
        }

        /** The field called {@code name}, or -1. */
        public int fieldIndex(String name) {
            for (int i = 0; i < fields.size(); i++) {
                if (fields.get(i).name().equals(name)) {
                    return i;
                }
            }
            return -1;
        }

        /** The slot offset of field {@code i} inside the struct. */
        public int offsetOf(int i) {
            int offset = 0;
            for (int k = 0; k < i; k++) {
                offset += fields.get(k).type().slots();
            }
            return offset;
        }

        @Override
        public int slots() {
            return fields.stream().mapToInt(f -> f.type().slots()).sum();
        }

        @Override
        public String toString() {
            StringBuilder sb = new StringBuilder("struct {");
            for (Field f : fields) {
                sb.append(' ').append(f.type()).append(' ').append(f.name()).append(';');
            }
            return sb.append(" }").toString();
        }
    }

    /** A field of a struct. */
    record Field(String name, Type type) {
    }

    /** The return type of functions that return nothing. */
    record Void() implements Type {
        /** The one void type. */
        public static final Void INSTANCE = new Void();

        @Override
        public int slots() {
            return 0;
        }

        @Override
        public String toString() {
            return "void";
        }
    }

    /**
     * A boolean formula over clocks: the type of {@code x <= 5}, {@code x - y > 2} and their conjunctions.
     *
     * @param kind what the formula may be used as
     */
    record ClockConstraint(ConstraintKind kind) implements Type {
        @Override
        public int slots() {
            return 0;
        }

        @Override
        public String toString() {
            return "clock constraint";
        }
    }

    /** Where a clock formula may stand (Uppaal's classification). */
    enum ConstraintKind {
        /**
         * Bounds {@code <, <=, >=, >} on clocks and clock differences, their conjunctions, and disjunctions with
         * conditions on data: usable as an invariant or a guard.
         */
        INVARIANT,
        /** As {@link #INVARIANT}, with {@code ==} on clocks too: usable as a guard. */
        GUARD,
        /** Anything else ({@code !=}, disjunctions of clock constraints, negations): usable in queries only. */
        CONSTRAINT
    }
}
