package io.dtron.engine.internal.eval;

import java.util.Arrays;

/**
 * The clock bounds of a guard or invariant, listed without a zone: each is {@code x_i - x_j ⋈ c} as a clock
 * pair and a raw {@link io.dtron.engine.internal.zone.Bound} in ticks ({@code j} or {@code i} is 0 for a bound on one
 * clock). The evaluator appends; the caller reads and clears. Reusable without allocating.
 */
public final class ClockBounds {
    private int[] entries = new int[24];
    private int size;

    void add(int i, int j, int raw) {
        if (3 * size + 3 > entries.length) {
            entries = Arrays.copyOf(entries, entries.length * 2);
        }
        entries[3 * size] = i;
        entries[3 * size + 1] = j;
        entries[3 * size + 2] = raw;
        size++;
    }

    /** The number of bounds listed. */
    public int size() {
        return size;
    }

    /** The clock {@code i} of bound {@code k}. */
    public int i(int k) {
        return entries[3 * checkIndex(k)];
    }

    /** The clock {@code j} of bound {@code k}. */
    public int j(int k) {
        return entries[3 * checkIndex(k) + 1];
    }

    /** The raw bound of {@code x_i - x_j} of bound {@code k}. */
    public int bound(int k) {
        return entries[3 * checkIndex(k) + 2];
    }

    /** Forgets every bound. */
    public void clear() {
        size = 0;
    }

    private int checkIndex(int k) {
        if (k < 0 || k >= size) {
            throw new IndexOutOfBoundsException("bound " + k + " of " + size);
        }
        return k;
    }
}
