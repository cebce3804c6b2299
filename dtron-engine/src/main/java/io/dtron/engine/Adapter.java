package io.dtron.engine;

/**
 * The engine's view of the system under test, shaped like Uppaal TRON's adapter API but typed: the engine
 * asks the adapter to {@link #perform} inputs; the adapter reports outputs through its {@link AdapterContext}
 * whenever the system produces them. An in-process sample system, the bus bridge and TRON's socket protocol
 * are all adapters.
 */
public interface Adapter {

    /** Called once before the first input; keep the context to report outputs and to schedule timers. */
    void start(AdapterContext context);

    /** Applies an input to the system under test. Called on the engine's thread; must not block for long. */
    void perform(Event input);

    /** Called once at the end of the run (the verdict is known). */
    default void stop() {
    }
}
