package io.dtron.engine;

/** Follows a test run as it happens: for traces, progress lines and monitors. All methods are optional. */
public interface TestListener {

    /** An input was applied at {@code micros} since the start. */
    default void inputApplied(Event input, long micros) {
    }

    /**
     * Output {@code output}, observed at {@code micros} since the start, was allowed by the model (seen from the last
     * event before it) from {@code earliestMicros} to {@code latestMicros} since the start, -1 when the window stays
     * open to the end of the test: the window of its channel that holds {@code micros}, or, for an output at a time
     * the model did not allow it, the next window after it, else the last one before it. Called just before {@link
     * #outputObserved}, and not at all when the model allowed no such output before the end of the test, or when the
     * output reached the tester after later events or after an event whose verdict waits for the reorder window (on a
     * bus).
     */
    default void outputWindow(Event output, long micros, long earliestMicros, long latestMicros) {
    }

    /** An output was observed at {@code micros} since the start. */
    default void outputObserved(Event output, long micros) {
    }

    /**
     * The tester waits, from {@code nowMicros} since the start, for outputs until {@code untilMicros}: the time of
     * its next input, the deadline by which the model requires an output, or the end of the test, as {@code until}
     * says. Called on the tester's thread before every wait; for progress lines, so it must return at once.
     */
    default void waiting(long nowMicros, long untilMicros, Until until) {
    }

    /**
     * The tester committed to {@code event} (an input when {@code input}) at {@code micros}: the edges it took for
     * certain (every state kept after it took them), and those it possibly took (some did, or the delays and internal
     * moves before it may have), as {@code Lamp: off -> low i_press?}. For coverage in traces.
     */
    default void edgesTaken(Event event, boolean input, long micros, java.util.List<String> certainly,
                            java.util.List<String> possibly) {
    }

    /** The run ended. */
    default void finished(TestResult result) {
    }

    /** What ends a wait of the tester, unless an output comes first. */
    enum Until {
        /** The tester applies its next input. */
        INPUT,
        /** The model requires an output by then; without one the run fails. */
        OUTPUT_DEADLINE,
        /** The timeout: the run passes. */
        END
    }
}
