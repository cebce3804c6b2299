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
}
