package io.dtron.engine;

import io.dtron.model.TestInterface;

/** What an {@link Adapter} gets from the engine: a way to report outputs, the run's clock and the interface. */
public interface AdapterContext {

    /**
     * Reports an output of the system under test, time-stamped with the clock's current time. Thread-safe; in
     * virtual time, call it from a task scheduled on {@link #clock()} or from {@link Adapter#perform}.
     */
    void report(Event output);

    /**
     * Reports an output of the system under test that happened at {@code eventMicros} on the run's clock
     * (microseconds since time 0), as its adapter stamped it. Thread-safe. Outputs may arrive out of the order of
     * their times: the tester places each by its time, as long as it arrives within the run's reorder window
     * ({@link TestOptions#reorderWindowMicros()}); one that arrives later, after events the tester already committed
     * to, ends the run INCONCLUSIVE, naming its delay.
     */
    void report(Event output, long eventMicros);

    /**
     * Reports an output, as {@link #report(Event, long)} does, whose time is known only within {@code
     * uncertaintyMicros} of {@code eventMicros}: the clocks of the adapter's host and the tester's agree only that
     * well. The tester accepts the output if the model allows it at some time in that interval (as TRON does for
     * observations). This implementation ignores the uncertainty.
     *
     * @throws IllegalArgumentException if the uncertainty is negative
     */
    default void report(Event output, long eventMicros, long uncertaintyMicros) {
        if (uncertaintyMicros < 0) {
            throw new IllegalArgumentException("negative uncertainty: " + uncertaintyMicros);
        }
        report(output, eventMicros);
    }

    /**
     * Reports that input number {@code ordinal} (1 for the first input the engine passed to {@link Adapter#perform},
     * 2 for the next, ...) was applied to the system under test at {@code eventMicros} on the run's clock, later than
     * the engine performed it. Thread-safe. The tester then places the input at that time (an input is never placed
     * before the time it was performed, or for one performed ahead, its due time); if the environment did not allow
     * it then, the run ends INCONCLUSIVE (the input was executed too late), never FAILED.
     */
    void inputApplied(long ordinal, long eventMicros);

    /**
     * Reports when an input was applied, as {@link #inputApplied(long, long)} does, known only within {@code
     * uncertaintyMicros} of {@code eventMicros}; the tester places the input at the time in that interval that the
     * environment allows, if any. This implementation ignores the uncertainty.
     *
     * @throws IllegalArgumentException if the uncertainty is negative or the ordinal not positive
     */
    default void inputApplied(long ordinal, long eventMicros, long uncertaintyMicros) {
        if (uncertaintyMicros < 0) {
            throw new IllegalArgumentException("negative uncertainty: " + uncertaintyMicros);
        }
        inputApplied(ordinal, eventMicros);
    }

    /**
     * Widens the run's reorder window to at least {@code micros} from now on, when messages take longer than it
     * allowed for (thread-safe); never narrows it. The tester then holds its judgement that much longer. This
     * implementation does nothing: the window stays as the run's options set it.
     */
    default void widenReorderWindow(long micros) {
    }

    /**
     * Ends the run INCONCLUSIVE with {@code reason} (thread-safe): the adapter lost the system under test (a
     * connection dropped, an adapter process left the bus) and the test cannot go on.
     */
    void inconclusive(String reason);

    /** The run's clock. */
    TestClock clock();

    /** The observable interface of the model: the channel and variable names events use. */
    TestInterface testInterface();

    /** Microseconds per model time unit in this run. */
    long timeUnitMicros();

    /**
     * The end of the run on its clock, in microseconds since time 0: the tester judges no event after it (a stop
     * condition may end the run earlier); {@link Long#MAX_VALUE} when the run has no such end. By default none.
     */
    default long endMicros() {
        return Long.MAX_VALUE;
    }
}
