package io.dtron.junit;

import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronOptions;
import io.dtron.engine.TestResult;
import java.util.Optional;

/**
 * One run of a {@link DtronTest} over a DTRON bus, in real time: its seed and goal, its bus, and the way to test the
 * systems behind bus adapters with them. A {@code @DtronTest} method takes it as its parameter (instead of a {@link
 * DtronRun}) and calls {@link #test} once. Needs {@code io.dtron:dtron-core} on the test classpath.
 *
 * <pre>{@code
 * @DtronTest(model = "lamp.xta", seeds = 3, timeUnit = 20_000, timeout = 100)
 * void lamp(DtronBusRun run) {
 *     run.test(new LampBusAdapter());
 * }
 * }</pre>
 */
public interface DtronBusRun {
    /** The seed of this run. */
    long seed();

    /** The goal this run steers toward, or empty when the test has none. */
    Optional<String> goal();

    /** The bus's name: {@link DtronTest#cluster()}, or the fresh name this run made. */
    String cluster();

    /**
     * Options for another member of this run's bus (an adapter the test connects itself): the cluster name, and the
     * NATS servers of {@link DtronTest#nats()} or JGroups on loopback. A new builder every call.
     */
    DtronOptions.Builder memberOptions();

    /**
     * Joins the bus as the tester, connects each of {@code adapters} to it as a member of its own in this JVM and
     * starts it, waits until every channel of the model is served (by them, or by adapters already on the bus or
     * joining it: with none given, only those), tests in real time, and returns the result when it PASSED. The
     * adapters are closed and leave the bus before it returns.
     *
     * @throws AssertionError when the run is FAILED: the message is the verdict's explanation and the seed
     * @throws RuntimeException when the run is INCONCLUSIVE (the message its reason), the model cannot be run, or the
     *                          bus is not ready within {@link DtronTest#busWait()} (the message says what is missing)
     * @throws IllegalStateException when this run already tested
     */
    TestResult test(DtronAdapter... adapters);
}
