package io.dtron.engine.internal.clock;

import io.dtron.engine.internal.tester.Plan;

/**
 * Not API. The engine's time scale: zones count integer ticks, {@code perUnit} to a model time unit of {@code
 * unitMicros} microseconds, so that an observed time in microseconds falls between two ticks. The tester, the
 * controller and the monitor convert their times with it.
 *
 * @param unitMicros the model time unit, in microseconds
 * @param perUnit    ticks per time unit
 */
public record Ticks(long unitMicros, int perUnit) {
    /** The most ticks to a time unit: a microsecond each for units up to a millisecond. */
    public static final int MAX_PER_UNIT = 1000;

    /** The scale of a time unit: a tick a microsecond, {@link #MAX_PER_UNIT} at most. */
    public static Ticks of(long unitMicros) {
        return new Ticks(unitMicros, (int) Math.min(unitMicros, MAX_PER_UNIT));
    }

    /** The last tick at or before {@code micros}. */
    public long floor(long micros) {
        return Math.floorDiv(micros * perUnit, unitMicros);
    }

    /** The first tick at or after {@code micros}. */
    public long ceil(long micros) {
        return -Math.floorDiv(-micros * perUnit, unitMicros);
    }

    /** The microseconds of {@code ticks}, rounded down. */
    public long microsFloor(long ticks) {
        return Math.floorDiv(ticks * unitMicros, perUnit);
    }

    /** The microseconds of {@code ticks}, rounded up. */
    public long micros(long ticks) {
        return -Math.floorDiv(-ticks * unitMicros, perUnit);
    }

    /** "t=12.500": a time in microseconds as the explanations say it, in time units. */
    public String time(long micros) {
        return "t=" + Plan.units(micros, unitMicros);
    }
}
