package io.dtron.cli;

import io.dtron.engine.monitor.Monitor;
import java.io.PrintWriter;
import java.time.Duration;
import java.util.Locale;

/**
 * The progress lines of {@code dtron monitor --replay}, so that the replay of a long trace does not look hung: every
 * {@link Progress#EVERY} of wall-clock time (the clock is read every {@value #CHECKED} lines) the time so far, the line
 * read, the trace's time, and the monitor's counts.
 */
final class ReplayProgress {
    /** How many lines are read between two looks at the clock: a look costs about 1% of a line's check. */
    static final int CHECKED = 256;
    private final PrintWriter out;
    private final long unitMicros;
    private final long everyNanos;
    private final long beganNanos = System.nanoTime();
    private long nextNanos;
    private int lines;

    /** Lines on {@code out} every {@code every}, with times in units of {@code unitMicros}. */
    ReplayProgress(PrintWriter out, long unitMicros, Duration every) {
        this.out = out;
        this.unitMicros = unitMicros;
        this.everyNanos = every.toNanos();
        this.nextNanos = beganNanos + everyNanos;
    }

    /**
     * After line {@code line} of the trace was read ({@code micros}: the latest time of the trace so far, negative
     * before its first event): prints a line when it is time to.
     */
    void after(int line, long micros, Monitor monitor, int rejected) {
        if (++lines % CHECKED != 0) {
            return;
        }
        long now = System.nanoTime();
        if (now - nextNanos < 0) {
            return;
        }
        nextNanos = now + everyNanos;
        out.println(String.format(Locale.ROOT, "progress: %.0f s, line %d", (now - beganNanos) / 1e9, line)
                + (micros >= 0 ? ", t=" + MonitorCommand.units(micros, unitMicros) : "") + ", "
                + MonitorCommand.events(monitor.events()) + ", " + MonitorCommand.violations(monitor.violations())
                + ", " + MonitorCommand.rejected(rejected));
        out.flush();
    }
}
