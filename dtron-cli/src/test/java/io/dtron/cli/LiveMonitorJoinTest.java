package io.dtron.cli;

import static io.dtron.cli.MonitorOnBus.REQ;
import static io.dtron.cli.MonitorOnBus.RESP;
import static io.dtron.cli.MonitorOnBus.UNIT_NANOS;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --cluster NAME} joins a running system (no run start on the bus): a request stamped before the
 * monitor began to watch, then its response in time, are both judged, with no alarm and nothing too late to judge.
 * The system's member stamps the times, the request's 100 ms before the monitor was even started (so that it took
 * more than half the reorder window, which widens, as a note among the alarms says), and a run's start then ends the
 * watch, which judges what it holds at once: no reorder window, however wide load made it, decides what the test
 * sees (the shield test failed by chance when the monitor's thread began after the first request; this test itself
 * failed under load when it waited for a window made seconds wide by a slow start).
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class LiveMonitorJoinTest {

    @Test
    void anEventStampedBeforeTheJoiningMonitorBeganIsJudged(@TempDir Path dir) throws Exception {
        MonitorOnBus monitor = new MonitorOnBus(dir, "join");
        try (Dtron system = monitor.member()) {
            long before = system.currentTimeNanos() - UNIT_NANOS;
            Path alarms = dir.resolve("alarms.jsonl");
            monitor.start(system, 2, "--timeunit", "100000", "--duration", "60", "--alarms", alarms.toString());
            // the model: a response 1 to 3 units after its request
            system.send(REQ.constructValued(Map.of("n", 1)), before);
            system.send(RESP.constructValued(Map.of("n", 2)), before + 2 * UNIT_NANOS);
            // a run starts: the watch of the running system ends, its events judged
            system.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 100_000)), system.currentTimeNanos());
            assertEquals(0, monitor.exit(), monitor.shown());
            assertTrue(monitor.shown().contains("the watch ended: no violation, 2 events checked (the next run started"
                    + " before its end), 0 too late to judge"), monitor.shown());
            // the request took longer than half the window (it was stamped before the monitor joined): the note
            // that the window widened is printed and written among the alarms, which are none
            List<String> lines = Files.readAllLines(alarms);
            assertTrue(lines.stream().allMatch(l -> l.startsWith("{\"kind\":\"note\",\"text\":\""))
                    && lines.stream().anyMatch(l -> l.contains("reorder window widened")), lines + "\n"
                    + monitor.shown());
        }
    }
}
