package io.dtron.junit;

import io.dtron.engine.Adapter;
import io.dtron.engine.TestResult;
import java.util.Optional;

/**
 * One run of a {@link DtronTest}: its seed and goal, and the way to test a system with them. A {@code @DtronTest}
 * method takes it as its parameter and calls {@link #test} once.
 */
public interface DtronRun {
    /** The seed of this run. */
    long seed();

    /** The goal this run steers toward, or empty when the test has none. */
    Optional<String> goal();

    /**
     * Tests {@code system} against the model and returns the result when it PASSED.
     *
     * @throws AssertionError when the run is FAILED: the message is the verdict's explanation and the seed
     * @throws RuntimeException when the run is INCONCLUSIVE (the message its reason), the model cannot be run, or the
     *                          system failed
     * @throws IllegalStateException when this run already tested a system
     */
    TestResult test(Adapter system);
}
