package io.dtron.junit;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.RunClock;
import java.util.Map;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * The system of lamp.xta behind a bus adapter, using nothing of DTRON but its adapter API: every press toggles it,
 * and it shows its new level {@code delayUnits} time units later by the bus's run clock (the model allows 1 to 2).
 *
 * <p>It checks its own timing: a light it showed more than {@value #HELD_UP_UNITS} time units after it was due, or
 * one still not shown that long after when the run ends, is counted in {@link #heldUp()} (the JVM held its
 * timer up), so that a FAILED verdict of the correct lamp can be told apart: the lamp was late, or the verdict wrong.
 */
final class LampBusAdapter implements DtronAdapter {
    static final IDtronChannel PRESS = IDtronChannel.of("press");
    static final IDtronChannel LIGHT = IDtronChannel.of("light", "level");
    /** How late a light may be before this lamp counts itself held up (the correct lamp's is 0.5 from the end). */
    static final double HELD_UP_UNITS = 0.25;
    private static final AtomicInteger HELD_UP = new AtomicInteger();

    private final double delayUnits;
    private Dtron dtron;
    private RunClock.Task pending;
    /** When the pending light is due, by {@link System#nanoTime()}. */
    private long dueNanos;
    private long unitNanos;
    private int level;

    LampBusAdapter(double delayUnits) {
        this.delayUnits = delayUnits;
    }

    @Override
    public synchronized void start(Dtron bus) {
        dtron = bus;
        bus.declareOutputs(LIGHT);
        bus.addDtronListener(new DtronListener(PRESS) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                pressed();
            }
        });
        bus.addDtronListener(new DtronListener(Dtron.RUN_STOP) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                stopped();
            }
        });
    }

    /** The run ended: a light due long before and never shown counts as held up. */
    private synchronized void stopped() {
        if (pending != null && late()) {
            heldUp("not shown by the end of the run");
        }
    }

    private synchronized void pressed() {
        RunClock clock = dtron.runClock();
        if (!clock.isRunning()) {
            return;
        }
        level = 1 - level;
        int shown = level;
        unitNanos = clock.timeUnitMicros() * 1000;
        dueNanos = System.nanoTime() + (long) (delayUnits * unitNanos);
        pending = clock.scheduleAt(clock.nowUnits() + delayUnits, () -> show(shown));
    }

    /** How many lights of these lamps came more than {@value #HELD_UP_UNITS} units late, or never, so far. */
    static int heldUp() {
        return HELD_UP.get();
    }

    /** Counts a light held up, and says so (a lamp in a JVM of its own says it to its output). */
    private void heldUp(String what) {
        HELD_UP.incrementAndGet();
        System.out.println("LampBusAdapter: a light was " + what + " more than " + HELD_UP_UNITS + " time units"
                + " after it was due: this JVM was held up");
    }

    private boolean late() {
        return System.nanoTime() - dueNanos > HELD_UP_UNITS * unitNanos;
    }

    private void show(int shown) {
        synchronized (this) {
            if (late()) {
                heldUp("shown");
            }
            pending = null;
        }
        try {
            dtron.send(LIGHT.constructValued(Map.of("level", shown)), dtron.currentTimeNanos());
        } catch (DtronException | IllegalStateException e) {
            // the run ended, or the adapter closed: nothing more to show
        }
    }

    @Override
    public synchronized void close() {
        if (pending != null) {
            pending.cancel();
        }
    }
}
