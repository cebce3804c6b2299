package io.dtron.engine;

import java.util.Objects;

/**
 * The settings of a test run.
 *
 * @param seed           the seed of the run's one random source (printed, so that a run can be replayed)
 * @param timeUnitMicros microseconds per model time unit
 * @param timeout        the test duration in model time units; the run passes when it is reached
 * @param delayPolicy    how input times are chosen
 * @param delayBound     for {@link DelayPolicy#RANDOM_BOUNDED}: the largest delay after a window opens, in model
 *                       time units
 * @param virtualTime    whether the run uses virtual time (deterministic, as fast as the CPU allows) rather
 *                       than real time
 * @param reorderWindowMicros how long, in microseconds, the tester holds its judgement of an event for messages
 *                       that happened before it but are still in transit (the reorder window Delta): observations
 *                       are placed by their own times, a deadline is declared missed only this long after it
 *                       passed, and a verdict is final only when no earlier event can still arrive. 0 for systems
 *                       under test that report in time order (in-process adapters)
 * @param inputMarginMicros in real time, how far inside the end of its window the tester aims an input, at least:
 *                       the tester's thread wakes up late (tens of microseconds on an idle machine, milliseconds on a
 *                       loaded one), and an input applied after its window ends makes the run INCONCLUSIVE. In a
 *                       window narrower than the margin the input is aimed at the window's start. During the run
 *                       the tester widens it to twice the latest it has woken up so far. Not used in virtual time
 * @param shortDelayBound for {@link DelayPolicy#RANDOM_BOUNDED}, when positive: each delay is bounded by this or by
 *                       {@code delayBound}, one of the two at random (TRON's {@code -P SHORT,LONG}); 0 for none
 */
public record TestOptions(long seed, long timeUnitMicros, long timeout, DelayPolicy delayPolicy, long delayBound,
                          boolean virtualTime, long reorderWindowMicros, long inputMarginMicros,
                          long shortDelayBound) {
    /** The input margin when none is given: 2 ms. */
    public static final long DEFAULT_INPUT_MARGIN_MICROS = 2000;

    /**
     * The longest run DTRON can time, in microseconds (about 292 years): the engine counts time in nanoseconds and
     * in up to 1000 ticks per time unit, so a duration in microseconds times 1000 must fit in a {@code long}. The
     * timeout and the delay bound, times the time unit, must not exceed it.
     */
    public static final long MAX_DURATION_MICROS = Long.MAX_VALUE / 1000;

    public TestOptions {
        Objects.requireNonNull(delayPolicy, "delayPolicy");
        if (timeUnitMicros <= 0) {
            throw new IllegalArgumentException("the time unit must be a positive number of microseconds");
        }
        if (timeout <= 0) {
            throw new IllegalArgumentException("the timeout must be a positive number of model time units");
        }
        if (delayBound < 0 || shortDelayBound < 0) {
            throw new IllegalArgumentException("the delay bound must not be negative");
        }
        if (reorderWindowMicros < 0 || reorderWindowMicros > MAX_DURATION_MICROS) {
            throw new IllegalArgumentException("the reorder window must be 0 to " + MAX_DURATION_MICROS + " us");
        }
        if (inputMarginMicros < 0 || inputMarginMicros > MAX_DURATION_MICROS) {
            throw new IllegalArgumentException("the input margin must be 0 to " + MAX_DURATION_MICROS + " us");
        }
        if (!fits(timeout, timeUnitMicros)) {
            throw new IllegalArgumentException(tooLong("the timeout", timeout, timeUnitMicros));
        }
        if (!fits(Math.max(delayBound, shortDelayBound), timeUnitMicros)) {
            throw new IllegalArgumentException(tooLong("the delay bound", delayBound, timeUnitMicros));
        }
    }

    /**
     * Whether {@code units} model time units of {@code timeUnitMicros} (positive) each last at most {@link
     * #MAX_DURATION_MICROS}, computed without overflow: for checking settings where they come in.
     */
    public static boolean fits(long units, long timeUnitMicros) {
        return units <= MAX_DURATION_MICROS / timeUnitMicros;
    }

    /** Why {@code units} time units of {@code timeUnitMicros} do not {@link #fits fit}, naming the limit. */
    public static String tooLong(String what, long units, long timeUnitMicros) {
        return what + " of " + units + " time units of " + timeUnitMicros + " us is longer than DTRON can time: at"
                + " most " + MAX_DURATION_MICROS + " us (about 292 years)";
    }

    /** Options without a short delay bound. */
    public TestOptions(long seed, long timeUnitMicros, long timeout, DelayPolicy delayPolicy, long delayBound,
                       boolean virtualTime, long reorderWindowMicros, long inputMarginMicros) {
        this(seed, timeUnitMicros, timeout, delayPolicy, delayBound, virtualTime, reorderWindowMicros,
                inputMarginMicros, 0);
    }

    /** Options with the {@link #DEFAULT_INPUT_MARGIN_MICROS default input margin}. */
    public TestOptions(long seed, long timeUnitMicros, long timeout, DelayPolicy delayPolicy, long delayBound,
                       boolean virtualTime, long reorderWindowMicros) {
        this(seed, timeUnitMicros, timeout, delayPolicy, delayBound, virtualTime, reorderWindowMicros,
                DEFAULT_INPUT_MARGIN_MICROS);
    }

    /** Options without a reorder window, for systems under test that report in time order. */
    public TestOptions(long seed, long timeUnitMicros, long timeout, DelayPolicy delayPolicy, long delayBound,
                       boolean virtualTime) {
        this(seed, timeUnitMicros, timeout, delayPolicy, delayBound, virtualTime, 0);
    }

    /** Options with defaults: random delays, virtual time, time unit 1000 us, timeout 1000 units. */
    public static TestOptions defaults(long seed) {
        return new TestOptions(seed, 1000, 1000, DelayPolicy.RANDOM, 0, true);
    }

    /** These options with another timeout (model time units). */
    public TestOptions withTimeout(long units) {
        return new TestOptions(seed, timeUnitMicros, units, delayPolicy, delayBound, virtualTime, reorderWindowMicros,
                inputMarginMicros, shortDelayBound);
    }

    /** These options with another time unit. */
    public TestOptions withTimeUnit(long micros) {
        return new TestOptions(seed, micros, timeout, delayPolicy, delayBound, virtualTime, reorderWindowMicros,
                inputMarginMicros, shortDelayBound);
    }

    /** These options with another delay policy and bound, and no short bound. */
    public TestOptions withDelayPolicy(DelayPolicy policy, long bound) {
        return new TestOptions(seed, timeUnitMicros, timeout, policy, bound, virtualTime, reorderWindowMicros,
                inputMarginMicros, 0);
    }

    /**
     * These options with delays bounded by {@code shortBound} or {@code longBound} (model time units), one of the two
     * at random for each delay, as TRON's {@code -P SHORT,LONG} chooses them.
     */
    public TestOptions withShortOrLongDelays(long shortBound, long longBound) {
        return new TestOptions(seed, timeUnitMicros, timeout, DelayPolicy.RANDOM_BOUNDED, longBound, virtualTime,
                reorderWindowMicros, inputMarginMicros, shortBound);
    }

    /** These options in real or virtual time. */
    public TestOptions withVirtualTime(boolean virtual) {
        return new TestOptions(seed, timeUnitMicros, timeout, delayPolicy, delayBound, virtual, reorderWindowMicros,
                inputMarginMicros, shortDelayBound);
    }

    /** These options with another reorder window (microseconds). */
    public TestOptions withReorderWindow(long micros) {
        return new TestOptions(seed, timeUnitMicros, timeout, delayPolicy, delayBound, virtualTime, micros,
                inputMarginMicros, shortDelayBound);
    }

    /** These options with another input margin (microseconds). */
    public TestOptions withInputMargin(long micros) {
        return new TestOptions(seed, timeUnitMicros, timeout, delayPolicy, delayBound, virtualTime, reorderWindowMicros,
                micros, shortDelayBound);
    }
}
