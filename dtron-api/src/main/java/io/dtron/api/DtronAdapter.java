package io.dtron.api;

/**
 * A bus adapter that a DTRON process can run in its own JVM, such as {@code dtron run MODEL --adapter CLASS}:
 * a class with a public no-argument constructor (and, for {@code CLASS:VARIANT}, a public constructor taking
 * the variant's name). The process connects a {@link Dtron} of the adapter's own to the run's bus, calls
 * {@link #start} with it before the run starts, {@link #close} after the run, and then closes the {@code Dtron}.
 */
public interface DtronAdapter extends AutoCloseable {

    /**
     * Starts the adapter: adds its listeners (typically on {@link Dtron#RUN_START} and the model's inputs) and
     * starts what it needs. Called once, before the run starts.
     */
    void start(Dtron dtron);

    /** Stops what the adapter started; the {@code Dtron} is closed by the caller. Does nothing by default. */
    @Override
    default void close() {
    }
}
