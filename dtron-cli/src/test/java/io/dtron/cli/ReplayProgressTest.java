package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.Event;
import io.dtron.engine.monitor.Monitor;
import io.dtron.engine.monitor.MonitorOptions;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.time.Duration;
import java.util.Map;
import org.junit.jupiter.api.Test;

/**
 * The progress lines of a replay ({@link ReplayProgress}), with a real monitor of the monitor tests' server model:
 * the clock is looked at every {@value ReplayProgress#CHECKED} lines, and a line says the line read, the trace's
 * time and the monitor's counts.
 */
class ReplayProgressTest {
    private static Monitor monitor() throws Exception {
        Network n = ModelLoader.load(MonitorCommandTest.SERVER);
        return Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(100_000));
    }

    @Test
    void aLineEveryTimeTheClockIsLookedAtWhenItIsDue() throws Exception {
        Monitor m = monitor();
        StringWriter text = new StringWriter();
        ReplayProgress progress = new ReplayProgress(new PrintWriter(text), 100_000, Duration.ZERO);
        for (int line = 1; line < ReplayProgress.CHECKED; line++) {
            progress.after(line, -1, m, 0);
        }
        assertEquals("", text.toString(), "no look at the clock before the 256th line");
        progress.after(ReplayProgress.CHECKED, -1, m, 0);
        assertTrue(text.toString().matches("progress: \\d+ s, line 256, 0 events checked, no violation, 0 lines"
                + " rejected\\R"), text.toString());
        m.observe(new Event("req", Map.of("n", 1)), 100_000);
        m.observe(new Event("resp", Map.of("n", 7)), 200_000);
        for (int line = ReplayProgress.CHECKED + 1; line <= 2 * ReplayProgress.CHECKED; line++) {
            progress.after(line + 1_000, 200_000, m, 1);
        }
        String[] lines = text.toString().split("\\R");
        assertEquals(2, lines.length, text.toString());
        assertTrue(lines[1].matches("progress: \\d+ s, line 1512, t=2\\.000, 2 events checked, 1 violation, 1 line"
                + " rejected"), text.toString());
    }

    @Test
    void noLineBeforeItsTime() throws Exception {
        Monitor m = monitor();
        StringWriter text = new StringWriter();
        ReplayProgress progress = new ReplayProgress(new PrintWriter(text), 100_000, Duration.ofHours(1));
        for (int line = 1; line <= 10 * ReplayProgress.CHECKED; line++) {
            progress.after(line, line, m, 0);
        }
        assertEquals("", text.toString());
    }
}
