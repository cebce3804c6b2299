package io.dtron.cli;

/** What a run uses for the settings that neither the user nor the model (or adapter) gives. */
final class RunDefaults {
    /** The longest wait in seconds an option may ask for: waits are timed in nanoseconds. */
    static final long MAX_WAIT_SECONDS = Long.MAX_VALUE / 1_000_000_000L;
    private static final long TIME_UNIT_MICROS = 1000;
    private static final long TIMEOUT_UNITS = 1000;

    private RunDefaults() {
    }

    /** The seed given, or one from the clock. */
    static long seed(Long given) {
        return given != null ? given : System.nanoTime() & 0xffffffffL;
    }

    /** The first time unit given (in microseconds), else 1 ms. */
    static long timeUnit(Long... given) {
        return first(given, TIME_UNIT_MICROS);
    }

    /** The first test duration given (in time units), else 1000 units. */
    static long timeout(Long... given) {
        return first(given, TIMEOUT_UNITS);
    }

    private static long first(Long[] given, long fallback) {
        for (Long value : given) {
            if (value != null) {
                return value;
            }
        }
        return fallback;
    }
}
