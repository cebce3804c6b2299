package io.dtron.bridge.internal;

import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Locale;
import java.util.OptionalLong;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. The reorder window of a bus run (Delta), in microseconds: how long the engine holds its judgement for
 * messages still in transit. Fixed ({@code --delta US}), or automatic: from the delays measured before the run, and
 * widened during it when a message takes more than half of it (to twice that message's delay, rounded up to a
 * millisecond), each widening said in a line. Thread-safe.
 */
public final class ReorderWindow {
    private static final Logger LOG = LoggerFactory.getLogger(ReorderWindow.class);
    /**
     * The smallest automatic window: a loaded host or a fresh JVM holds a message up for tens of milliseconds now
     * and then, whatever the bus's delays were before the run.
     */
    public static final long AUTO_FLOOR_MICROS = 50_000;
    /** How many times the longest delay measured before the run the automatic window allows for. */
    public static final int DELAY_FACTOR = 3;

    private final List<String> widenings = Collections.synchronizedList(new ArrayList<>());
    private volatile long micros;
    private volatile boolean auto;

    /**
     * The automatic window for delays measured before a run: {@value #DELAY_FACTOR} times the longest delay plus
     * twice the clocks' error bound, rounded up to a millisecond, and at least {@link #AUTO_FLOOR_MICROS}.
     */
    public static long auto(long maxDelayNanos, long maxErrorNanos) {
        long nanos = DELAY_FACTOR * maxDelayNanos + 2 * maxErrorNanos;
        long rounded = -Math.floorDiv(-nanos, 1_000_000L) * 1000;
        return Math.max(AUTO_FLOOR_MICROS, rounded);
    }

    /** Sets the window the next run starts with, and whether it widens during the run. */
    public void set(long windowMicros, boolean automatic) {
        micros = windowMicros;
        auto = automatic;
    }

    /** Returns the window now: as set, or as widened during the run. */
    public long micros() {
        return micros;
    }

    /** Whether the window widens during the run. */
    public boolean automatic() {
        return auto;
    }

    /** Forgets the widenings of the last run. */
    public void newRun() {
        widenings.clear();
    }

    /**
     * A message arrived {@code delayMicros} after its event, at {@code receivedMicros} on the run's clock: when the
     * window is automatic and the message took more than half of it, widens it and returns the new width.
     *
     * @param what what arrived ("output tick", "acknowledgement of move"), from whom, for the line that says it
     */
    public OptionalLong arrived(long delayMicros, long receivedMicros, String what) {
        long window = micros;
        if (!auto || window <= 0 || delayMicros <= window / 2) {
            return OptionalLong.empty();
        }
        long widened = -Math.floorDiv(-2 * delayMicros, 1000) * 1000;
        micros = widened;
        String line = String.format(Locale.ROOT, "to %.1f ms at run time %.3f s: %s took %.1f ms", widened / 1e3,
                receivedMicros / 1e6, what, delayMicros / 1e3);
        widenings.add(line);
        LOG.info("Reorder window widened {}", line);
        return OptionalLong.of(widened);
    }

    /** Returns how the window was widened during the last run, one line each; empty if it was not. */
    public List<String> widenings() {
        synchronized (widenings) {
            return List.copyOf(widenings);
        }
    }
}
