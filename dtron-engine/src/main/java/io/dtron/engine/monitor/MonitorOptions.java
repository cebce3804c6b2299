package io.dtron.engine.monitor;

import java.util.Objects;

/**
 * How a {@link Monitor} runs: the model's time unit, where it starts, and whether it goes on after a violation.
 * Immutable.
 *
 * @param timeUnitMicros one model time unit in microseconds
 * @param start          where the monitor starts
 * @param from           with {@link Start#FROM}, the state property (query language, as in {@code E<> P}) the
 *                       start states satisfy; else null
 * @param keepGoing      whether the monitor counts violations and re-synchronises after each ({@code --continue})
 *                       instead of stopping at the first
 */
public record MonitorOptions(long timeUnitMicros, Start start, String from, boolean keepGoing) {
    /** Where a monitor starts. */
    public enum Start {
        /** The model's initial state, at time 0 of the run clock. */
        INITIAL,
        /** Every state the model can reach, at the time of the first event or clock tick: history unknown. */
        ANY,
        /** The reachable states where {@link #from} holds, at the time of the first event or clock tick. */
        FROM
    }

    public MonitorOptions {
        if (timeUnitMicros <= 0) {
            throw new IllegalArgumentException("the time unit must be positive: " + timeUnitMicros);
        }
        Objects.requireNonNull(start, "start");
        if ((start == Start.FROM) != (from != null)) {
            throw new IllegalArgumentException("a state property goes with Start.FROM, and only with it");
        }
    }

    /** From the initial state, stopping at the first violation. */
    public static MonitorOptions initial(long timeUnitMicros) {
        return new MonitorOptions(timeUnitMicros, Start.INITIAL, null, false);
    }

    /** From every reachable state (history unknown), stopping at the first violation. */
    public static MonitorOptions anyState(long timeUnitMicros) {
        return new MonitorOptions(timeUnitMicros, Start.ANY, null, false);
    }

    /** From the reachable states where {@code property} holds, stopping at the first violation. */
    public static MonitorOptions from(long timeUnitMicros, String property) {
        return new MonitorOptions(timeUnitMicros, Start.FROM, Objects.requireNonNull(property, "property"), false);
    }

    /** These options, going on after violations (or not). */
    public MonitorOptions keepGoing(boolean keepGoing) {
        return new MonitorOptions(timeUnitMicros, start, from, keepGoing);
    }
}
