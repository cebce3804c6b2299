package io.dtron.engine;

/** Follows a test run as it happens: for traces, progress lines and monitors. All methods are optional. */
public interface TestListener {

    /** An input was applied at {@code micros} since the start. */
    default void inputApplied(Event input, long micros) {
    }

    /** An output was observed at {@code micros} since the start. */
    default void outputObserved(Event output, long micros) {
    }

    /** The run ended. */
    default void finished(TestResult result) {
    }
}
