package io.dtron.cli;

import static io.dtron.cli.MonitorOnBus.REQ;
import static io.dtron.cli.MonitorOnBus.RESP;
import static io.dtron.cli.MonitorOnBus.UNIT_NANOS;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.BusRecord;
import io.dtron.api.Dtron;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.internal.TesterSide;
import io.dtron.bridge.internal.ReorderWindow;
import io.dtron.testsupport.Waits;
import java.nio.file.Path;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --cluster NAME} asks the adapters, as the tester does, before it judges a deadline passed: a
 * real JGroups member on loopback plays the tester (the run's start, its requests and stop, with exact event times)
 * and another the server of the monitor tests' model (100 ms time units), so load changes nothing the tests assert.
 * A server held up as a busy JVM is (its response, stamped before the deadline, is published only when the monitor's
 * probe comes, a reorder window after the deadline, and the answer follows it) raises no alarm; a server that really
 * missed the deadline, and answers the probe at once, raises it at the deadline.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class LiveMonitorProbeTest {
    @TempDir
    Path dir;

    /** The monitor on its own thread, the tester's member and the server's. */
    private final class Watch implements AutoCloseable {
        final MonitorOnBus monitor;
        final Dtron tester;
        final Dtron server;
        final long t0;

        Watch() throws Exception {
            monitor = new MonitorOnBus(dir, "probe");
            tester = monitor.member();
            server = monitor.member();
            server.declareOutputs(RESP);
            monitor.start(tester, 3);
            TesterSide.of(tester).setRunId("c0ffee");
            t0 = tester.currentTimeNanos();
            // a request at 1: its response is due by 4; the run ends at 6
            TesterSide.of(tester).sendRunStart(Dtron.RUN_START.constructValued(Map.of("timeunit", 100_000)), t0,
                    t0 + 6 * UNIT_NANOS);
            IDtronChannelValued req = tester.send(REQ.constructValued(Map.of("n", 1)), t0 + UNIT_NANOS);
            tester.acknowledge(req, t0 + UNIT_NANOS);
            Waits.await("the server's clock offset to the tester").until(server::hasClockOffset);
        }

        /** Whether a record is a ping of the monitor (neither the tester's nor the server's). */
        boolean monitorsPing(BusRecord r) {
            return r.channel().equals("dtron_ping")
                    && !Set.of(tester.getMemberId(), server.getMemberId()).contains(r.sender());
        }

        /** Ends the run: its stop, once the wall clock passed the run's end; returns the monitor's exit code. */
        int stop() throws Exception {
            Waits.await("the wall clock past the run's end").until(() -> tester.currentTimeNanos()
                    > t0 + 8 * UNIT_NANOS);
            tester.send(Dtron.RUN_STOP.constructValued(Map.of()), t0 + 6 * UNIT_NANOS);
            return monitor.exit();
        }

        String shown() {
            return monitor.shown();
        }

        @Override
        public void close() {
            server.close();
            tester.close();
        }
    }

    @Test
    void aResponseStampedBeforeTheDeadlineThatComesBeforeTheProbesAnswerRaisesNoAlarm() throws Exception {
        try (Watch watch = new Watch()) {
            long heldUntil = watch.t0 + 4 * UNIT_NANOS + TimeUnit.MICROSECONDS.toNanos(
                    ReorderWindow.AUTO_FLOOR_MICROS);
            AtomicBoolean published = new AtomicBoolean();
            // held up: the response stamped at 2 leaves when the monitor asks, after the deadline and its window;
            // published on the receiving thread, it goes before the answer to the probe
            watch.server.addRecordListener(r -> {
                if (watch.monitorsPing(r) && watch.server.currentTimeNanos() > heldUntil
                        && published.compareAndSet(false, true)) {
                    watch.server.send(RESP.constructValued(Map.of("n", 2)), watch.t0 + 2 * UNIT_NANOS);
                }
            });
            int exit = watch.stop();
            String printed = watch.monitor.out.toString();
            assertTrue(published.get(), "the monitor asked the server after the deadline\n" + watch.shown());
            assertEquals(0, exit, watch.shown());
            assertFalse(printed.contains("violation 1"), watch.shown());
            assertTrue(printed.contains("run c0ffee ended: no violation, 2 events checked"), watch.shown());
        }
    }

    @Test
    void aServerThatMissedTheDeadlineRaisesTheAlarmAtTheDeadline() throws Exception {
        try (Watch watch = new Watch()) {
            int exit = watch.stop();
            String printed = watch.monitor.out.toString();
            assertEquals(2, exit, watch.shown());
            assertTrue(printed.contains("violation 1 at t=4.000: no event by t=4.000"), watch.shown());
            assertFalse(printed.contains("did not answer"), watch.shown());
        }
    }
}
