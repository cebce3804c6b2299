package io.dtron.engine.internal.clock;

/**
 * Not API. The time of a state set's elapsed clock's 0: {@code offsetTicks} whole ticks after {@code baseMicros}, so
 * that a reference moved on by whole ticks stays on one grid of ticks and no rounding of microseconds to ticks adds
 * up over many events. The tester and the monitor measure an event's window from it.
 *
 * @param ticks       the time scale
 * @param baseMicros  the time the ticks are counted from
 * @param offsetTicks the ticks from {@code baseMicros} to the reference
 */
public record Reference(Ticks ticks, long baseMicros, long offsetTicks) {
    /** The reference at {@code micros}. */
    public static Reference at(Ticks ticks, long micros) {
        return new Reference(ticks, micros, 0);
    }

    /** The last tick at or before {@code micros}, counted from the reference. */
    public long floor(long micros) {
        return ticks.floor(micros - baseMicros) - offsetTicks;
    }

    /**
     * The first tick of a window that begins at {@code micros}: the last tick at or before it, counted from the
     * reference, and not before the reference (0), where the time of the state set it is measured from starts.
     */
    public long windowStart(long micros) {
        return Math.max(0, floor(micros));
    }

    /** The first tick at or after {@code micros}, counted from the reference. */
    public long ceil(long micros) {
        return ticks.ceil(micros - baseMicros) - offsetTicks;
    }

    /** The microseconds of the reference (rounded up to a microsecond). */
    public long micros() {
        return micros(0);
    }

    /** The microseconds of {@code ticks} after the reference, rounded up. */
    public long micros(long ticksAfter) {
        return baseMicros + ticks.micros(offsetTicks + ticksAfter);
    }

    /** The microseconds of {@code ticks} after the reference, rounded down. */
    public long microsFloor(long ticksAfter) {
        return baseMicros + ticks.microsFloor(offsetTicks + ticksAfter);
    }

    /** The reference {@code ticksAfter} ticks later, on the same grid. */
    public Reference plus(long ticksAfter) {
        return new Reference(ticks, baseMicros, offsetTicks + ticksAfter);
    }
}
