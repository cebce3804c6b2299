package io.dtron.engine.internal.eval;

import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.xta.Pos;
import java.util.Arrays;

/**
 * The clock assignments that updates made, in order: clock index (1..n) and value in model time units. The
 * evaluator appends to it; the caller reads it, applies it to a zone and clears it. Reusable without
 * allocating once it has grown to the largest number of resets.
 */
public final class ClockResets {
    private int[] clocks = new int[8];
    private int[] values = new int[8];
    private Pos[] positions = new Pos[8];
    private int size;

    void add(int clock, int value, Pos pos) {
        if (size == clocks.length) {
            clocks = Arrays.copyOf(clocks, size * 2);
            values = Arrays.copyOf(values, size * 2);
            positions = Arrays.copyOf(positions, size * 2);
        }
        clocks[size] = clock;
        values[size] = value;
        positions[size] = pos;
        size++;
    }

    /** The number of resets recorded. */
    public int size() {
        return size;
    }

    /** The clock of reset {@code i}. */
    public int clock(int i) {
        return clocks[checkIndex(i)];
    }

    /** The value (in model time units, never negative) of reset {@code i}. */
    public int value(int i) {
        return values[checkIndex(i)];
    }

    /** Forgets every reset. */
    public void clear() {
        Arrays.fill(positions, 0, size, null);
        size = 0;
    }

    /**
     * Applies the resets in order to {@code zone}, with values scaled to {@code ticksPerUnit}.
     *
     * @throws ModelRuntimeException if a scaled value is beyond the zone's range
     */
    public void applyTo(Dbm zone, int ticksPerUnit) {
        for (int i = 0; i < size; i++) {
            zone.reset(clocks[i], ticks(i, ticksPerUnit));
        }
    }

    /**
     * The value of reset {@code i} scaled to {@code ticksPerUnit}.
     *
     * @throws ModelRuntimeException if it is beyond a zone's range
     */
    public int ticks(int i, int ticksPerUnit) {
        long ticks = (long) values[checkIndex(i)] * ticksPerUnit;
        if (ticks > Bound.MAX_VALUE) {
            throw new ModelRuntimeException(positions[i], "the clock value " + values[i]
                    + " is too large for the engine's time resolution (at most "
                    + Bound.MAX_VALUE / ticksPerUnit + " time units)");
        }
        return (int) ticks;
    }

    private int checkIndex(int i) {
        if (i < 0 || i >= size) {
            throw new IndexOutOfBoundsException("reset " + i + " of " + size);
        }
        return i;
    }
}
