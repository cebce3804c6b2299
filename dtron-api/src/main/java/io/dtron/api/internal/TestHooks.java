package io.dtron.api.internal;

import io.dtron.api.DtronOptions;
import java.time.Duration;
import java.util.Objects;
import java.util.function.BiConsumer;
import java.util.function.Function;

/**
 * Not API. The bus options that only DTRON's own tests set: a member whose wall clock is off by a given shift, as if
 * its host's clock were, for the tests of clock offsets and event times. Adapters have no use for them.
 */
public final class TestHooks {
    private static volatile BiConsumer<DtronOptions.Builder, Duration> setShift;
    private static volatile Function<DtronOptions, Duration> getShift;

    private TestHooks() {
    }

    /**
     * Called once, by {@link DtronOptions} as its class is initialised.
     *
     * @throws IllegalStateException when called again
     */
    public static synchronized void grant(BiConsumer<DtronOptions.Builder, Duration> setter,
            Function<DtronOptions, Duration> getter) {
        if (setShift != null) {
            throw new IllegalStateException("the test hooks are granted once, by DtronOptions");
        }
        setShift = setter;
        getShift = getter;
    }

    /**
     * Adds {@code shift} to every time the member of {@code options} reads from its wall clock (publish, event,
     * receive and ping times, the run clock), as if its host's clock were off by that much (default: zero).
     *
     * @return {@code options}
     */
    public static DtronOptions.Builder clockShift(DtronOptions.Builder options, Duration shift) {
        setShift.accept(Objects.requireNonNull(options, "options"), Objects.requireNonNull(shift, "shift"));
        return options;
    }

    /** Returns the shift added to the wall clock of the member of {@code options}; zero normally. */
    public static Duration clockShift(DtronOptions options) {
        return getShift.apply(options);
    }
}
