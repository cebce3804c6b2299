package io.dtron.cli;

import static io.dtron.cli.MonitorOnBus.RESP;
import static io.dtron.cli.MonitorOnBus.UNIT_NANOS;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.api.Dtron;
import io.dtron.testsupport.Waits;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.w3c.dom.Element;

/**
 * {@code dtron monitor --cluster NAME --runs 0} in a JVM of its own, stopped by a real SIGTERM (as a service manager
 * or {@code kill} stops it) while it watches: it still prints its summary, saying that it was interrupted, and writes
 * the JUnit report and the alarms it was asked for, with the violation it found (a response without a request) before
 * the signal. Before, the shutdown hook ended the watch but the JVM halted before the summary and the report.
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class LiveMonitorInterruptTest {

    @Test
    void aSignalledMonitorPrintsItsSummaryAndWritesItsReports(@TempDir Path dir) throws Exception {
        MonitorOnBus bus = new MonitorOnBus(dir, "interrupt");
        Path junit = dir.resolve("monitor.xml");
        Path alarms = dir.resolve("alarms.jsonl");
        try (Dtron system = bus.member();
                ChildJvm monitor = ChildJvm.start(DtronCommand.class, dir.resolve("monitor.log"), "monitor",
                        dir.resolve("server.xta").toString(), "--cluster", bus.cluster, "--timeunit", "100000",
                        "--runs", "0", "--junit", junit.toString(), "--alarms", alarms.toString())) {
            monitor.awaitOutput(" as dtron-", Duration.ofSeconds(90));
            Waits.await("the monitor among the members").until(() -> system.getMembers().size() == 2);
            // from every reachable state: a response may answer a request before the watch, a second one may not
            long now = system.currentTimeNanos();
            system.send(RESP.constructValued(Map.of("n", 2)), now);
            system.send(RESP.constructValued(Map.of("n", 3)), now + UNIT_NANOS);
            monitor.awaitOutput("violation 1 at", Waits.TIMEOUT);
            monitor.signal("-TERM");
            // a JVM ended by SIGTERM exits with 128 + 15, after its shutdown hooks
            assertEquals(143, monitor.waitFor(Duration.ofSeconds(60)), monitor.output());
            String shown = monitor.output();
            assertTrue(shown.contains("the watch ended: 1 violation"), shown);
            assertTrue(shown.contains("\ndtron monitor: interrupted, 1 run, 1 violation (the watch: 1), "), shown);
            Element suite = JunitReportTest.parse(junit).getDocumentElement();
            Element test = (Element) suite.getElementsByTagName("testcase").item(0);
            assertEquals("the watch", test.getAttribute("name"), shown);
            assertEquals(1, test.getElementsByTagName("failure").getLength(), shown);
            assertEquals("1", JunitReportTest.properties(suite).get("violations"), shown);
            assertTrue(suite.getElementsByTagName("system-out").item(0).getTextContent()
                    .startsWith("dtron monitor: interrupted, "), shown);
            assertTrue(Files.readString(alarms).contains("\"kind\":\"alarm\",\"number\":1,"), shown);
        }
    }
}
