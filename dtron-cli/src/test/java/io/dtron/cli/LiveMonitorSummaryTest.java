package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.bridge.BusMonitor;
import io.dtron.bridge.BusMonitor.End;
import io.dtron.bridge.BusMonitor.RunResult;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The live monitor's line at the end: the runs with each one's violations, and of more than ten runs those with
 * violations, the others counted.
 */
class LiveMonitorSummaryTest {
    @Test
    void eachRunsViolationsAndOfManyRunsThoseWithViolations() {
        List<RunResult> two = List.of(new RunResult("a1", 0, 11, 0, 0, End.STOPPED, 0, null),
                new RunResult("b2", 1, 0, 0, 0, End.FIRST_VIOLATION, 0, null));
        assertEquals("dtron monitor: 2 runs, 1 violation (run a1: 0, run b2: 1), 11 events checked, 0 too late to"
                + " judge", LiveMonitor.summary(new BusMonitor.Result(two, null), false, false));
        assertEquals("dtron monitor: 1 run, 1 violation (the watch: 1), 3 events checked, 0 too late to judge, 1"
                + " withheld", LiveMonitor.summary(new BusMonitor.Result(List.of(new RunResult("", 1, 3, 0, 1,
                End.WATCH_ENDED, 0, null)), null), true, false));
        List<RunResult> many = new ArrayList<>();
        for (int i = 0; i < 12; i++) {
            many.add(new RunResult("r" + i, i == 4 ? 2 : 0, 1, i == 7 ? 1 : 0, 0, End.STOPPED, i == 9 ? 2 : 0, null));
        }
        assertEquals("dtron monitor: 12 runs, 2 violations (11 runs without violations, run r4: 2), 12 events checked,"
                + " 1 too late to judge, 2 after the run's end (not judged)", LiveMonitor.summary(new BusMonitor.Result(
                many, null), false, false));
    }
}
