package io.dtron.cli;

import static io.dtron.cli.MonitorOnBus.REQ;
import static io.dtron.cli.MonitorOnBus.RESP;
import static io.dtron.cli.MonitorOnBus.UNIT_NANOS;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.internal.TesterSide;
import io.dtron.testsupport.Waits;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --cluster NAME} prints a progress line every five seconds while it watches, whether or not
 * anything happens: a real JGroups member on loopback plays the tester and the server of the monitor tests' model
 * (100 ms time units), one request and its response, then nothing until the stop. The lines repeat, so the test waits
 * for the first that counts both events, whenever load lets the monitor judge them. The watch's {@code --junit}
 * report holds the run as a passing test case.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class LiveMonitorProgressTest {
    private static final Pattern BOTH_JUDGED = Pattern.compile("progress: (\\d+) s watching, run c0ffee judged to"
            + " t=(\\d+)\\.\\d{3}, 2 events checked, no violation, 0 too late to judge\n");

    @TempDir
    Path dir;

    @Test
    void aWatchShowsHowFarItJudgedEveryFiveSeconds() throws Exception {
        MonitorOnBus monitor = new MonitorOnBus(dir, "progress");
        try (Dtron system = monitor.member()) {
            monitor.start(system, 2, "--junit", dir.resolve("watch.xml").toString());
            TesterSide.of(system).setRunId("c0ffee");
            long t0 = system.currentTimeNanos();
            TesterSide.of(system).sendRunStart(Dtron.RUN_START.constructValued(Map.of("timeunit", 100_000)), t0,
                    t0 + 1_000 * UNIT_NANOS);
            IDtronChannelValued req = system.send(REQ.constructValued(Map.of("n", 1)), t0 + UNIT_NANOS);
            system.acknowledge(req, t0 + UNIT_NANOS);
            system.send(RESP.constructValued(Map.of("n", 2)), t0 + 25 * UNIT_NANOS / 10);
            Waits.await("a progress line with both events judged").atMost(java.time.Duration.ofSeconds(90))
                    .until(() -> BOTH_JUDGED.matcher(lines(monitor)).find());
            Matcher line = BOTH_JUDGED.matcher(lines(monitor));
            assertTrue(line.find(), monitor.shown());
            assertTrue(Integer.parseInt(line.group(1)) >= 5, "the first line after five seconds: " + monitor.shown());
            assertTrue(Integer.parseInt(line.group(2)) >= 2, "judged past the response at t=2.5: " + monitor.shown());
            system.send(Dtron.RUN_STOP.constructValued(Map.of()), system.currentTimeNanos());
            assertEquals(0, monitor.exit(), monitor.shown());
            String printed = lines(monitor);
            assertTrue(printed.indexOf("progress: ") < printed.indexOf("run c0ffee ended: no violation, 2 events"
                    + " checked"), monitor.shown());
        }
        // --junit: the run a passing test case, the counts as properties
        String xml = Files.readString(dir.resolve("watch.xml"));
        assertTrue(xml.contains("<testsuite name=\"dtron monitor " + dir.resolve("server.xta") + "\" tests=\"1\""
                + " failures=\"0\" errors=\"0\""), xml);
        assertTrue(xml.contains("<testcase name=\"run c0ffee\" classname=\"dtron.monitor.server\""), xml);
        assertTrue(xml.contains("<property name=\"events\" value=\"2\"/>"), xml);
        assertTrue(xml.contains("<property name=\"runs\" value=\"1\"/>"), xml);
    }

    private static String lines(MonitorOnBus monitor) {
        return monitor.out.toString().replace(System.lineSeparator(), "\n");
    }
}
