package io.dtron.engine.internal.zone;

/**
  * Raw encoding of one bound {@code x_i - x_j < c} or {@code x_i - x_j <= c} as an {@code int}.
  *
  * <p>A finite bound with value {@code c} is encoded as {@code (c << 1) | (strict ? 0 : 1)}, and
  * {@link #INFINITY} ({@code < inf}) is larger than every finite bound. The natural {@code int}
  * order of raw bounds is therefore the order of tightness: a smaller raw bound is a stronger
  * constraint ({@code <5} before {@code <=5} before {@code <6}), so {@link Math#min(int, int)} of
  * two raw bounds is their conjunction.
  *
  * <p>Finite values must lie in {@code [-MAX_VALUE, MAX_VALUE]} (about {@code ±2^30}). {@link
  * #add(int, int)} never overflows: a sum above the range becomes {@link #INFINITY} and a sum below
  * it is clamped to {@code < -MAX_VALUE}; both only weaken a constraint.
  */
public final class Bound {

    /** Largest absolute value of a finite bound: {@code 2^30 - 2}. */
    public static final int MAX_VALUE = (1 << 30) - 2;

    /** The absent bound {@code < inf}; larger than every finite raw bound. */
    public static final int INFINITY = Integer.MAX_VALUE - 1;

    /** The raw bound {@code <= 0}. */
    public static final int LE_ZERO = 1;

    /** The raw bound {@code < 0}. */
    public static final int LT_ZERO = 0;

    private static final int MAX_RAW = (MAX_VALUE << 1) | 1;
    private static final int MIN_RAW = -MAX_VALUE << 1;

    private Bound() {}

    /**
      * Returns the raw bound {@code < value} or {@code <= value}.
      *
      * @throws IllegalArgumentException if {@code |value| > MAX_VALUE}
      */
    public static int of(int value, boolean strict) {
        if (value > MAX_VALUE || value < -MAX_VALUE) {
            throw new IllegalArgumentException("bound value out of range: " + value);
        }
        return strict ? value << 1 : (value << 1) | 1;
    }

    /** Returns the raw non-strict bound {@code <= value}; see {@link #of(int, boolean)}. */
    public static int le(int value) {
        return of(value, false);
    }

    /** Returns the raw strict bound {@code < value}; see {@link #of(int, boolean)}. */
    public static int lt(int value) {
        return of(value, true);
    }

    /**
      * Returns the value {@code c} of a finite raw bound.
      *
      * @throws IllegalArgumentException if {@code raw} is {@link #INFINITY}
      */
    public static int value(int raw) {
        if (raw == INFINITY) {
            throw new IllegalArgumentException("infinite bound has no value");
        }
        return raw >> 1;
    }

    /** Returns whether the raw bound is strict ({@code <}); {@link #INFINITY} is strict. */
    public static boolean isStrict(int raw) {
        return (raw & 1) == 0;
    }

    /** Returns whether the raw bound is {@link #INFINITY}. */
    public static boolean isInfinite(int raw) {
        return raw == INFINITY;
    }

    /**
      * Returns the sum of two raw bounds: the values add, and the sum is strict if either is strict.
      * Infinity absorbs; see the class comment for sums beyond the range.
      */
    public static int add(int a, int b) {
        if (a == INFINITY || b == INFINITY) {
            return INFINITY;
        }
        long sum = (long) a + b - ((a | b) & 1);
        if (sum > MAX_RAW) {
            return INFINITY;
        }
        return sum < MIN_RAW ? MIN_RAW : (int) sum;
    }

    /**
      * Compares two raw bounds by tightness: negative if {@code a} is the stronger constraint, zero
      * if equal, positive if {@code a} is the weaker.
      */
    public static int compare(int a, int b) {
        return Integer.compare(a, b);
    }

    /** Returns the raw bound as text: {@code "<5"}, {@code "<=-2"}, {@code "<inf"}. */
    public static String toString(int raw) {
        if (raw == INFINITY) {
            return "<inf";
        }
        return (isStrict(raw) ? "<" : "<=") + (raw >> 1);
    }
}
