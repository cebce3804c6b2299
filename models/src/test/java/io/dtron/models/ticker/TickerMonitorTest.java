package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --replay} on the traces of the README's ticker run, on the bus in real time: the monitor
 * agrees with the tester on every run (no violation where the tester PASSED, a violation at the tester's failing
 * event where the ticker was held up and the tester FAILED), and finds the slow ticker's late tick at the event the
 * tester failed. Each event's time is taken within the clock error its sender stamped on the bus, as the tester
 * judges it.
 */
@Timeout(value = 300, unit = TimeUnit.SECONDS)
class TickerMonitorTest {
    private static final String MODEL = "src/main/resources/io/dtron/models/ticker.xml";
    private static final Pattern ERROR = Pattern.compile("\"error_ns\":(\\d+)");
    private static final Pattern VIOLATION = Pattern.compile("(?m)^violation 1 at t=(\\d+)\\.(\\d{3}): .*");

    record Run(int exit, String out, Path trace) {
    }

    private static Run run(Path dir, String variant, int n) {
        Path trace = dir.resolve(variant + "-" + n + ".jsonl");
        String[] args = {MODEL, "--adapter", TickerBusAdapter.class.getName() + ":" + variant, "--timeunit", "10000",
                "--timeout", "300", "--delay-policy", "eager", "--cluster",
                "monitor-" + UUID.randomUUID().toString().substring(0, 8), "--trace", trace.toString()};
        StringWriter out = new StringWriter();
        int exit = DtronCommand.run(args, new PrintWriter(out), new PrintWriter(new StringWriter()));
        return new Run(exit, out.toString(), trace);
    }

    /**
     * Replays {@code trace} with each event's time give or take the largest clock error its bus lines carry, and no
     * more: the tester and the monitor keep each event's window on the same ticks, so the tester's eager inputs
     * keep the model's bounds by the events' stamps.
     */
    private static Run monitor(Path trace) throws Exception {
        long errorNanos = 0;
        Matcher m = ERROR.matcher(Files.readString(trace));
        while (m.find()) {
            errorNanos = Math.max(errorNanos, Long.parseLong(m.group(1)));
        }
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int exit = DtronCommand.run(new String[] {"monitor", MODEL, "--replay", trace.toString(), "--tolerance",
                String.valueOf((errorNanos + 999) / 1000)}, new PrintWriter(out),
                new PrintWriter(err));
        assertEquals("", err.toString(), "no line rejected");
        return new Run(exit, out.toString(), trace);
    }

    /** The time, in microseconds, of the last output line of {@code trace}: the event the tester failed. */
    private static long lastOutput(Path trace) throws Exception {
        List<String> outputs = Files.readAllLines(trace).stream().filter(l -> l.startsWith("{\"kind\":\"output\""))
                .toList();
        Matcher m = Pattern.compile("\"t_us\":(\\d+)").matcher(outputs.get(outputs.size() - 1));
        assertTrue(m.find());
        return Long.parseLong(m.group(1));
    }

    @Test
    void theMonitorAgreesWithTheTesterOnTenRunsOfTheReadmeCommand(@TempDir Path dir) throws Exception {
        int passed = 0;
        for (int n = 1; n <= 10; n++) {
            Run tester = run(dir, "correct", n);
            if (tester.exit() == 3) {
                continue; // INCONCLUSIVE: not every event was judged
            }
            Run monitor = monitor(tester.trace());
            if (tester.exit() == 0) {
                passed++;
                assertEquals(0, monitor.exit(), "run " + n + " PASSED, yet:\n" + monitor.out() + tester.out());
            } else {
                // a ticker held up beyond the model's bound (TickerBusAdapterTest): the monitor sees the late tick too
                assertEquals(2, tester.exit(), tester.out());
                assertEquals(2, monitor.exit(), "run " + n + " FAILED, yet:\n" + monitor.out() + tester.out());
            }
        }
        assertTrue(passed > 0, "no run PASSED");
    }

    @Test
    void theSlowTickersLateTickIsFoundWhereTheTesterFailedIt(@TempDir Path dir) throws Exception {
        Run tester = run(dir, "slow", 1);
        assertEquals(2, tester.exit(), tester.out());
        Run monitor = monitor(tester.trace());
        assertEquals(2, monitor.exit(), monitor.out());
        Matcher m = VIOLATION.matcher(monitor.out());
        assertTrue(m.find(), monitor.out());
        long alarm = Long.parseLong(m.group(1)) * 10_000 + Long.parseLong(m.group(2)) * 10;
        long late = lastOutput(tester.trace());
        // the deadline the late tick missed: before the tick, and at most the model's 2 units of tolerance earlier
        assertTrue(alarm <= late && alarm > late - 30_000, "alarm at " + alarm + " us, the late tick at " + late
                + " us:\n" + monitor.out());
        assertTrue(monitor.out().contains("the next event, tick(seq=1), came at"), monitor.out());
    }
}
