package io.dtron.engine;

import java.util.Optional;

/**
 * The engine's view of the system under test, shaped like Uppaal TRON's adapter API but typed: the engine
 * asks the adapter to {@link #perform} inputs; the adapter reports outputs through its {@link AdapterContext}
 * whenever the system produces them. An in-process sample system, the bus bridge and TRON's socket protocol
 * are all adapters.
 */
public interface Adapter {

    /**
     * Called once before time 0 of the run, before {@link #timeZero()} and {@link #start}: what the adapter does to
     * get ready that should not take the run's time (on a bus, its view of the members and what they serve). Nothing
     * by default.
     */
    default void prepare() {
    }

    /** Called once before the first input; keep the context to report outputs and to schedule timers. */
    void start(AdapterContext context);

    /** Applies an input to the system under test. Called on the engine's thread; must not block for long. */
    void perform(Event input);

    /**
     * Asked before the engine declares that the system under test missed a deadline: why the system may have been
     * unable to act, as far as the adapter knows (a member of the bus that does not answer, a lost connection), or
     * empty when nothing is known against it. With a reason the run ends INCONCLUSIVE naming it, not FAILED. May
     * take a moment to find out (a probe of the adapter's processes); by default nothing is known.
     */
    default Optional<String> unreachable() {
        return Optional.empty();
    }

    /**
     * Returns when the run's time 0 is, as a {@link System#nanoTime()} reading, when the adapter agreed on it with
     * others before the run (several testers of one run start their engines at one time 0); in real time the
     * engine then counts from that instant, waiting for it if it lies ahead. Empty by default: time 0 is when the
     * engine starts. Asked once, after the engine prepared its first step.
     */
    default java.util.OptionalLong timeZero() {
        return java.util.OptionalLong.empty();
    }

    /**
     * Returns whether the adapter reports when it applied each input ({@link AdapterContext#inputApplied}): then a
     * verdict that depends on where an input was applied waits a while for that report. False by default.
     */
    default boolean acknowledgesInputs() {
        return false;
    }

    /**
     * Returns how long an input on {@code channel} (its name, as {@link Event#channel()}) may take from {@link
     * #perform} until the system under test has it, in microseconds, with the error of the clocks that measured it:
     * the tester aims every input on the channel that much further inside the end of its window (at the window's
     * start when the window is narrower), so that it lands inside. Asked before every choice of an input, so it may
     * change during a run; must return at once. 0 by default (an adapter in the tester's process applies an input
     * when it is performed).
     */
    default long inputDelayMicros(String channel) {
        return 0;
    }

    /**
     * Returns how long before its time an input on {@code channel} may be performed with {@link #perform(Event,
     * long)}, in microseconds: the adapter hands it to the system under test at that time, not before, so that the
     * input's way to the system is taken before its time instead of after it. The tester then performs such an input
     * this much ahead (and aims it its lateness margin and {@link #inputDelayMicros} inside the end of its window, the
     * latter for how exactly the adapter keeps the time). Asked before every input; must return at once. 0 by
     * default: inputs are performed at their time.
     */
    default long inputLeadMicros(String channel) {
        return 0;
    }

    /**
     * Applies an input at run time {@code dueMicros}, which may lie up to {@link #inputLeadMicros} ahead: the
     * adapter holds it until then (or applies it on arrival when that is later). By default {@link #perform(Event)}
     * at once, for adapters whose lead is 0.
     */
    default void perform(Event input, long dueMicros) {
        perform(input);
    }

    /** Called once at the end of the run (the verdict is known). */
    default void stop() {
    }

    /**
     * Called once at the end of a test run whose verdict is known, instead of {@link #stop()}: {@code
     * observedUntilMicros} is the time on the run's clock up to which the tester judged the events (its timeout, or
     * its verdict's time when that came first), so that others who watch the run can judge up to the same instant.
     * By default {@link #stop()}.
     */
    default void stop(long observedUntilMicros) {
        stop();
    }
}
