package io.dtron.cli;

import static io.dtron.cli.MonitorOnBus.REQ;
import static io.dtron.cli.MonitorOnBus.RESP;
import static io.dtron.cli.MonitorOnBus.UNIT_NANOS;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.internal.TesterSide;
import io.dtron.testsupport.Waits;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --cluster NAME} judges a run up to the tester's end of observation, which the run's start
 * announces and its stop carries: a real JGroups member on loopback plays the tester and the server of the monitor
 * tests' model (100 ms time units), publishing the run's messages with exact event times, so load changes nothing
 * the tests assert. An event stamped after the end, and a deadline after it, are not judged even though the stop
 * comes later (the tester judged neither); an event stamped before the end that the bus delivers after the stop is
 * judged; a monitor that joins during the run learns the announced end from the tester's pongs; a stop of a tester
 * that announced no end (an older one) ends the run when it was published, as before.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class LiveMonitorRunEndTest {
    @TempDir
    Path dir;

    /** The monitor on its own thread, and the member that publishes the run. */
    private final class Watch implements AutoCloseable {
        final MonitorOnBus monitor;
        final Dtron system;

        Watch(String... options) throws Exception {
            monitor = new MonitorOnBus(dir, "runend");
            system = monitor.member();
            monitor.start(system, 2, options);
            TesterSide.of(system).setRunId("c0ffee");
        }

        /** The monitor's exit code, once the run's watch ended. */
        int exit() throws Exception {
            return monitor.exit();
        }

        String shown() {
            return monitor.shown();
        }

        /** Publishes an event at {@code atNanos}; a request, the run's start's sender's input, is applied then. */
        void send(IDtronChannel channel, int n, long atNanos) {
            IDtronChannelValued sent = system.send(channel.constructValued(Map.of("n", n)), atNanos);
            if (channel == REQ) {
                system.acknowledge(sent, atNanos);
            }
        }

        /**
         * Starts a run now, in time units of 100 ms, announcing its end {@code endUnits} later; returns its time 0 and
         * its end.
         */
        long[] startRun(int endUnits) {
            long t0 = system.currentTimeNanos();
            long end = t0 + endUnits * UNIT_NANOS;
            TesterSide.of(system).sendRunStart(Dtron.RUN_START.constructValued(Map.of("timeunit", 100_000)), t0, end);
            return new long[] {t0, end};
        }

        /** Waits until the wall clock has passed {@code nanos}, so that the monitor's time may have passed it. */
        void awaitPast(long nanos) {
            Waits.await("the wall clock past the run's end").until(() -> system.currentTimeNanos() > nanos);
        }

        @Override
        public void close() {
            system.close();
        }
    }

    @Test
    void anEventAndADeadlineAfterTheTestersEndAreNotJudgedThoughTheStopComesLater() throws Exception {
        try (Watch watch = new Watch()) {
            long[] run = watch.startRun(5);
            long t0 = run[0];
            long end = run[1];
            // a request at 3.5: its response is due by 6.5, after the end at 5; the response at 7, after the end
            watch.send(REQ, 1, t0 + 35 * UNIT_NANOS / 10);
            watch.send(RESP, 2, t0 + 7 * UNIT_NANOS);
            // the stop comes well after the response's deadline, as a held-up tester's would
            watch.awaitPast(t0 + 12 * UNIT_NANOS);
            watch.system.send(Dtron.RUN_STOP.constructValued(Map.of()), end);
            int exit = watch.exit();
            String printed = watch.monitor.out.toString();
            assertEquals(0, exit, watch.shown());
            assertFalse(printed.contains("violation 1"), watch.shown());
            assertTrue(printed.contains("run c0ffee ended: no violation, 1 event checked (the run ended), 0 too late"
                    + " to judge, 1 after the run's end (not judged)"), watch.shown());
            assertTrue(printed.contains("dtron monitor: 1 run, no violation (run c0ffee: 0), 1 event checked, 0 too"
                    + " late to judge, 1 after the run's end (not judged)"), watch.shown());
        }
    }

    @Test
    void aTestersInputStampedBeforeAJudgedEventIsPlacedByItsAcknowledgementNotTakenAsLate() throws Exception {
        try (Watch watch = new Watch()) {
            long[] run = watch.startRun(5);
            long t0 = run[0];
            long end = run[1];
            watch.send(REQ, 1, t0 + UNIT_NANOS);
            watch.send(RESP, 2, t0 + 2 * UNIT_NANOS);
            // once the monitor judged the response at 2 (its window is over), the tester's next request comes,
            // stamped at 1.9 (the tester aimed it there), and its adapter applied it at 2.2: it happened at 2.2, after
            // the response, as the tester takes it (a web adapter applies an input a little after its stamp)
            watch.awaitPast(t0 + 2 * UNIT_NANOS + 2 * LiveMonitor.AUTO_WINDOW_MICROS * 1000);
            IDtronChannelValued late = watch.system.send(REQ.constructValued(Map.of("n", 3)),
                    t0 + 19 * UNIT_NANOS / 10);
            watch.system.acknowledge(late, t0 + 22 * UNIT_NANOS / 10);
            watch.awaitPast(end);
            watch.system.send(Dtron.RUN_STOP.constructValued(Map.of()), end);
            int exit = watch.exit();
            String printed = watch.monitor.out.toString();
            assertEquals(0, exit, watch.shown());
            assertTrue(printed.contains("run c0ffee ended: no violation, 3 events checked (the run ended), 0 too late"
                    + " to judge"), watch.shown());
        }
    }

    @Test
    void anEventStampedBeforeTheEndThatTheBusDeliversAfterTheStopIsJudged() throws Exception {
        Path xml = dir.resolve("watch.xml");
        try (Watch watch = new Watch("--junit", xml.toString())) {
            long[] run = watch.startRun(5);
            long t0 = run[0];
            long end = run[1];
            watch.send(REQ, 1, t0 + UNIT_NANOS);
            watch.system.send(Dtron.RUN_STOP.constructValued(Map.of()), end);
            // after the stop on the bus, stamped at 1.5: half a unit after the request, before the server's 1
            watch.send(RESP, 2, t0 + 15 * UNIT_NANOS / 10);
            int exit = watch.exit();
            String printed = watch.monitor.out.toString();
            assertEquals(2, exit, watch.shown());
            assertTrue(printed.contains("violation 1 at t=1.500: resp(n=2)"), watch.shown());
            assertTrue(printed.contains("1 violation, 2 events checked"), watch.shown());
            assertFalse(printed.contains("after the run's end"), watch.shown());
        }
        // --junit: the run a test case, failed with its violation
        org.w3c.dom.Element suite = JunitReportTest.parse(xml).getDocumentElement();
        assertEquals(List.of("1", "1", "0"), List.of(suite.getAttribute("tests"), suite.getAttribute("failures"),
                suite.getAttribute("errors")));
        assertEquals("run c0ffee", ((org.w3c.dom.Element) suite.getElementsByTagName("testcase").item(0))
                .getAttribute("name"));
        String failure = ((org.w3c.dom.Element) suite.getElementsByTagName("failure").item(0)).getAttribute("message");
        assertTrue(failure.startsWith("violation 1 at t=1.500: resp(n=2)"), failure);
    }

    @Test
    void aMonitorThatJoinsDuringARunLearnsItsAnnouncedEndFromTheTester() throws Exception {
        MonitorOnBus monitor = new MonitorOnBus(dir, "joinend");
        try (Dtron system = monitor.member()) {
            TesterSide.of(system).setRunId("c0ffee");
            long t0 = system.currentTimeNanos();
            long end = t0 + 100 * UNIT_NANOS;
            TesterSide.of(system).sendRunStart(Dtron.RUN_START.constructValued(Map.of("timeunit", 100_000)), t0, end);
            // the monitor joins after the start, which it never sees: the tester's answers to its pings say the end
            monitor.start(system, 2, "--timeunit", "100000");
            // a request 1.5 units before the end: its response is due 1.5 units after it, which the tester did not
            // judge; the stop comes well after that deadline, as a held-up tester's would
            IDtronChannelValued request = system.send(REQ.constructValued(Map.of("n", 1)), end - 15 * UNIT_NANOS / 10);
            system.acknowledge(request, end - 15 * UNIT_NANOS / 10);
            Waits.await("the wall clock past the run's end").until(() -> system.currentTimeNanos()
                    > end + 12 * UNIT_NANOS);
            system.send(Dtron.RUN_STOP.constructValued(Map.of()), end);
            assertEquals(0, monitor.exit(), monitor.shown());
            String printed = monitor.out.toString();
            assertFalse(printed.contains("violation 1"), monitor.shown());
            assertTrue(printed.contains("run c0ffee ended: no violation, 1 event checked (the run ended), 0 too late"
                    + " to judge"), monitor.shown());
        }
    }

    @Test
    void eachRunsJunitCaseTakesItsOwnTimeNotTheWholeWatchs() throws Exception {
        Path xml = dir.resolve("runs.xml");
        try (Watch watch = new Watch("--runs", "2", "--junit", xml.toString())) {
            for (int n = 0; n < 2; n++) {
                long[] run = watch.startRun(3);
                long t0 = run[0];
                long end = run[1];
                watch.send(REQ, 1, t0 + UNIT_NANOS);
                watch.send(RESP, 2, t0 + 2 * UNIT_NANOS);
                watch.awaitPast(end);
                watch.system.send(Dtron.RUN_STOP.constructValued(Map.of()), end);
                int ended = n + 1;
                Waits.await("the run's end").until(() -> watch.monitor.out.toString().split(" ended: ").length > ended);
            }
            assertEquals(0, watch.exit(), watch.shown());
        }
        org.w3c.dom.Element suite = JunitReportTest.parse(xml).getDocumentElement();
        double whole = Double.parseDouble(suite.getAttribute("time"));
        org.w3c.dom.NodeList cases = suite.getElementsByTagName("testcase");
        assertEquals(2, cases.getLength());
        double sum = 0;
        for (int i = 0; i < 2; i++) {
            double own = Double.parseDouble(((org.w3c.dom.Element) cases.item(i)).getAttribute("time"));
            assertTrue(own > 0, "run " + i + " took " + own + " s");
            sum += own;
        }
        // the runs followed one another within the watch: their times add up to no more than the watch's (each was
        // the whole watch's before)
        assertTrue(sum <= whole + 0.002, "runs " + sum + " s, the watch " + whole + " s");
    }

    @Test
    void aStopOfATesterThatAnnouncedNoEndEndsTheRunWhenItWasPublished() throws Exception {
        try (Watch watch = new Watch()) {
            long t0 = watch.system.currentTimeNanos();
            // an older tester: a start without an end, a stop stamped when it is published
            watch.system.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 100_000)), t0);
            watch.send(REQ, 1, t0 + 35 * UNIT_NANOS / 10);
            watch.awaitPast(t0 + 12 * UNIT_NANOS);
            watch.system.send(Dtron.RUN_STOP.constructValued(Map.of()));
            int exit = watch.exit();
            assertEquals(2, exit, watch.shown());
            assertTrue(watch.monitor.out.toString().contains("violation 1 at t=6.500: no event by t=6.500"), watch.shown());
        }
    }
}
