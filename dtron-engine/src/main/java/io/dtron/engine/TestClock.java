package io.dtron.engine;

/**
 * The time of a test run, in microseconds since its start. In virtual time it advances only when the
 * engine lets it (deterministically, as fast as the CPU allows); in real time it is the wall clock. Adapters
 * that need time (timers of a simulated system under test) schedule through it, so that they run in virtual
 * time too.
 */
public interface TestClock {

    /** Microseconds since the start of the run. */
    long nowMicros();

    /**
     * Runs {@code task} once, {@code delayMicros} from now (0 = as soon as possible, after the current
     * step). Tasks due at the same time run in the order they were scheduled. Tasks never run concurrently with
     * each other or with the engine's own steps.
     */
    Scheduled schedule(long delayMicros, Runnable task);

    /** A scheduled task. */
    interface Scheduled {
        /** Prevents the task from running if it has not run yet. */
        void cancel();
    }
}
