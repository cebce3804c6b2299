package io.dtron.junit;

import io.dtron.junit.internal.DtronExtension;
import java.lang.annotation.Documented;
import java.lang.annotation.ElementType;
import java.lang.annotation.Retention;
import java.lang.annotation.RetentionPolicy;
import java.lang.annotation.Target;
import org.junit.jupiter.api.TestTemplate;
import org.junit.jupiter.api.extension.ExtendWith;

/**
 * Tests a system under test against an Uppaal model, once per seed (and per goal): each run is a test of its own,
 * named by its seed ({@code seed 4711}, with a goal {@code seed 4711, goal E<> Lamp.bright}), that fails with the
 * verdict's explanation. The method takes a {@link DtronRun} and hands it the system (an {@link
 * io.dtron.engine.Adapter} in the test's JVM), a fresh one for every run:
 *
 * <pre>{@code
 * @DtronTest(model = "lamp.xta", seeds = 20)
 * void lamp(DtronRun run) {
 *     run.test(new Lamp());
 * }
 * }</pre>
 *
 * <p>Runs are in virtual time: deterministic and as fast as the CPU allows, for a system that does everything
 * that takes time through its {@link io.dtron.engine.AdapterContext#clock() clock}. A FAILED run fails its test
 * (an {@link AssertionError}, a {@code <failure>} in Surefire's report); an INCONCLUSIVE one is an error (a {@code
 * <error>}), which fails the build too: the test said nothing about the system. The seed of a run that did not pass
 * is stored in {@code .dtron/failed-seeds.properties} (system property {@code dtron.seedFile}) and runs first the
 * next time, until it passes; every run's events and verdict are written to {@code
 * target/dtron-reports/CLASS/METHOD-seed-SEED.txt} (system property {@code dtron.reportDirectory}), beside
 * Surefire's reports.
 *
 * <p>A method that takes a {@link DtronBusRun} instead tests systems behind bus adapters ({@link
 * io.dtron.api.DtronAdapter}), in real time, on a bus of the run's own: by default JGroups on loopback under a fresh
 * {@link #cluster() cluster} name, or the NATS servers of {@link #nats()}. It needs {@code io.dtron:dtron-core} on the
 * test classpath; {@link #virtualTime()} does not apply to it.
 */
@Target(ElementType.METHOD)
@Retention(RetentionPolicy.RUNTIME)
@Documented
@TestTemplate
@ExtendWith(DtronExtension.class)
public @interface DtronTest {
    /**
     * The model (.xml, .xta or .ta): a resource on the test's classpath, relative to the test class's package or,
     * starting with {@code /}, absolute; else a file, relative to the project's folder.
     */
    String model();

    /** A TRON interface file (.trn), found as {@link #model()} is; empty (the default): the i_/o_ channel names. */
    String interfaceFile() default "";

    /** How many runs, each with a seed of its own (default 10). Seeds that failed last time are among them, first. */
    int seeds() default 10;

    /** The seed of the first run, the next ones counting up from it; -1 (the default): new seeds every time. */
    long seed() default -1;

    /** The test duration of each run in model time units; 0 (the default): the interface file's, else 1000. */
    long timeout() default 0;

    /** Microseconds per model time unit; 0 (the default): the interface file's precision, else 1000. */
    long timeUnit() default 0;

    /**
     * Test purposes ({@code E<> P} in Uppaal's syntax): each run steers toward one of them and passes when it is
     * reached; one test per seed and goal. None (the default): each run tests until the timeout.
     */
    String[] goals() default {};

    /**
     * Whether the runs are in virtual time (the default) rather than in real time. Runs over the bus ({@link
     * DtronBusRun}) are in real time whatever this says: the adapters live in real time.
     */
    boolean virtualTime() default true;

    /**
     * Over the bus: the bus's cluster name, for adapters started elsewhere under a name they know; empty (the
     * default): a fresh name for every run ({@code dtron-junit-} and a random part), so that runs never meet.
     */
    String cluster() default "";

    /**
     * Over the bus: the NATS servers' URLs ({@code nats://127.0.0.1:4222}); none (the default): those of the system
     * property {@code dtron.nats} (comma-separated), so that a CI job with a NATS server can run the suite's bus tests
     * over it, else JGroups on loopback. Each fresh cluster name makes a stream on the server, whose messages expire
     * after 10 minutes; {@link #cluster()} keeps to one.
     */
    String[] nats() default {};

    /** Over the bus: how many seconds a run waits until every channel of the model is served (default 30). */
    int busWait() default 30;
}
