package io.dtron.models.streetlight;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.engine.monitor.Alarm;
import io.dtron.engine.monitor.Monitor;
import io.dtron.engine.monitor.MonitorOptions;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/**
 * A monitor of the street lights that does not know the run's history: it starts from every reachable state (about
 * 125,000 symbolic states) in the middle of a run, lets time pass between the events, takes each event's time give
 * or take half a time unit, and forgets what it learnt halfway (as a live monitor does after a message too late to
 * judge). The closures from every reachable state visit more states than a step of a run from the initial state
 * may, and must still be followed.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class StreetLightMonitorTest {
    private static final long TIME_UNIT = StreetLightModel.TIME_UNIT_MICROS;

    private record Timed(Event event, long micros) {
    }

    @ParameterizedTest(name = "seed {0}")
    @ValueSource(longs = {1, 2})
    void aMonitorWithoutTheHistoryFollowsACorrectRun(long seed, @TempDir Path dir) throws Exception {
        Network network = ModelLoader.load(StreetLightModel.write(dir, 2));
        List<Timed> run = run(network, false, seed);
        Alarm alarm = monitorFromTheMiddle(network, run);
        assertNull(alarm, () -> alarm.explanation());
    }

    @ParameterizedTest(name = "seed {0}")
    @ValueSource(longs = {1, 2})
    void aMonitorWithoutTheHistoryFindsTheMixUpAtTheResultTheTesterFailed(long seed, @TempDir Path dir)
            throws Exception {
        Network network = ModelLoader.load(StreetLightModel.write(dir, 2));
        List<Timed> run = run(network, true, seed);
        Alarm alarm = monitorFromTheMiddle(network, run);
        assertNotNull(alarm, "no alarm on the run the tester failed");
        Timed failed = run.get(run.size() - 1);
        assertEquals(failed.event(), alarm.event(), alarm.explanation());
        assertEquals(failed.micros(), alarm.micros(), alarm.explanation());
    }

    /**
     * The first alarm of a monitor from every reachable state that sees the run from its fifth event on, forgetting
     * what it learnt at the middle event; time passes between two events in two steps.
     */
    private static Alarm monitorFromTheMiddle(Network network, List<Timed> run) throws ModelException {
        Monitor monitor = Monitor.of(network, TestInterface.fromNames(network), MonitorOptions.anyState(TIME_UNIT));
        long last = run.get(3).micros();
        for (int i = 4; i < run.size(); i++) {
            Timed t = run.get(i);
            if (i == run.size() / 2) {
                monitor.forgetHistory();
            }
            Alarm late = monitor.advanceTo(last + (t.micros() - last) / 2);
            if (late != null) {
                return late;
            }
            Alarm alarm = monitor.observe(t.event(), t.micros(), TIME_UNIT / 2);
            if (alarm != null) {
                return alarm;
            }
            last = t.micros();
        }
        return null;
    }

    /** A run of the tester against the simulated application: its events with their times. */
    private static List<Timed> run(Network network, boolean mixUp, long seed) throws ModelException {
        List<Timed> events = new ArrayList<>();
        TestOptions options = TestOptions.defaults(seed).withTimeUnit(TIME_UNIT).withTimeout(300)
                .withDelayPolicy(DelayPolicy.RANDOM_BOUNDED, 4);
        OnlineTester tester = new OnlineTester(network, TestInterface.fromNames(network),
                new SimulatedStreetLights(mixUp), options);
        tester.addListener(new TestListener() {
            @Override
            public void inputApplied(Event input, long micros) {
                events.add(new Timed(input, micros));
            }

            @Override
            public void outputObserved(Event output, long micros) {
                events.add(new Timed(output, micros));
            }
        });
        TestResult result = tester.run();
        assertEquals(mixUp ? Verdict.FAILED : Verdict.PASSED, result.verdict(), result.explanation());
        return events;
    }
}
