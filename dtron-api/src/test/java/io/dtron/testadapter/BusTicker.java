package io.dtron.testadapter;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A ticker on the bus for the ticker model, using only {@code io.dtron.api}: from the start of a run it publishes
 * {@code tick(seq)} every 10 time units ({@code slow}: 13), and restarts on {@code reset}, until the run stops;
 * the first period counts from the run's time 0 (the event time of its start), and a period after a reset from when
 * this adapter applied the reset, as it acknowledges it (counting from the reset's publish time would tick early by
 * the reset's way here: a false FAILED when that way takes more than the model's tolerance).
 *
 * <p>It checks its own timing: a tick it published more than {@value #TOLERANCE} time units away from its period
 * after the previous tick or reset, or one that was that overdue when the run stopped (its timer thread was held
 * up, as on a loaded machine), is logged as a warning "(this JVM was held up)" and counted in {@link #heldUpTicks()}:
 * then a FAILED verdict is the right one for a late system, and a test can tell it from a false one.
 */
public final class BusTicker implements DtronAdapter {
    private static final IDtronChannel RESET = IDtronChannel.of("reset");
    private static final IDtronChannel TICK = IDtronChannel.of("tick", "seq");
    /** The model's tolerance either side of the period, in time units. */
    static final int TOLERANCE = 2;
    private static final Logger LOG = LoggerFactory.getLogger(BusTicker.class);
    /** The ticks of every ticker in this JVM that were held up past the tolerance. */
    private static final AtomicInteger HELD_UP = new AtomicInteger();

    private final int periodUnits;
    private final ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(task -> {
        Thread thread = new Thread(task, "bus-ticker");
        thread.setDaemon(true);
        return thread;
    });
    private final AtomicInteger resets = new AtomicInteger();
    private Dtron dtron;
    private long periodMicros;
    private double unitMicros = 1;
    private ScheduledFuture<?> ticking;
    private long generation;
    private int seq;
    /** When the last tick or reset happened (or the run's time 0), on this member's clock; 0 while not ticking. */
    private long lastNanos;

    /** The correct ticker. */
    public BusTicker() {
        this("correct");
    }

    /** A variant: "correct" or "slow". */
    public BusTicker(String variant) {
        periodUnits = switch (variant) {
            case "correct" -> 10;
            case "slow" -> 13;
            default -> throw new IllegalArgumentException("unknown variant '" + variant + "' (correct, slow)");
        };
    }

    @Override
    public synchronized void start(Dtron bus) {
        dtron = bus;
        bus.declareOutputs(TICK);
        bus.addDtronListener(new DtronListener(Dtron.RUN_START) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                restart(periodUnits * (long) message.getVariables().get("timeunit"),
                        message.getEventTimeNanos() + message.getClockOffsetNanos() - dtron.getClockOffsetNanos());
            }
        });
        bus.addDtronListener(new DtronListener(Dtron.RUN_STOP) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                stop(message.getEventTimeNanos() + message.getClockOffsetNanos() - dtron.getClockOffsetNanos());
            }
        });
        bus.addDtronListener(new DtronListener(RESET) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                reset(message);
            }
        });
    }

    private synchronized void reset(IDtronChannelValued message) {
        resets.incrementAndGet();
        restart(periodMicros, 0);
    }

    /** Stops ticking until the next run starts (the run's tester left, say): a tick due by now is not judged. */
    public synchronized void stop() {
        stop(0);
    }

    /**
     * Stops ticking; a tick overdue at {@code endNanos} on this member's clock (the run's end, 0 for unknown) was
     * held up.
     */
    private synchronized void stop(long endNanos) {
        if (endNanos != 0 && periodMicros > 0 && lastNanos != 0) {
            double overdue = units(endNanos - lastNanos) - periodUnits;
            if (overdue > TOLERANCE) {
                heldUp("Tick " + (seq + 1) + " was due " + String.format(Locale.ROOT, "%.3f", overdue) + " time units"
                        + " before the run stopped and had not been published, beyond the tolerance of " + TOLERANCE);
            }
        }
        lastNanos = 0;
        generation++;
        if (ticking != null) {
            ticking.cancel(false);
        }
        periodMicros = 0;
    }

    /**
     * Returns how many ticks of the tickers in this JVM were held up: published, or overdue when their run stopped,
     * more than the model's tolerance away from their period after the previous tick or reset. A test that runs a
     * ticker in its own JVM reads it before and after a run: a FAILED verdict is right when it grew.
     */
    public static int heldUpTicks() {
        return HELD_UP.get();
    }

    /** Returns how many resets arrived. */
    public int resets() {
        return resets.get();
    }

    @Override
    public synchronized void close() {
        // a tick overdue now, when the run ended before this ticker heard of it, never comes: held up
        if (dtron != null) {
            stop(dtron.currentTimeNanos());
        }
        timer.shutdownNow();
    }

    /**
     * Starts a period at {@code fromEpochNanos} on this member's clock (the run's time 0, exact on one host), or now
     * when it is 0.
     */
    private synchronized void restart(long period, long fromEpochNanos) {
        if (timer.isShutdown() || period == 0) {
            return;
        }
        long now = dtron.currentTimeNanos();
        long age = fromEpochNanos == 0 ? 0 : (now - fromEpochNanos) / 1000;
        long firstDelay = period - Math.max(0, Math.min(period / 2, age));
        if (ticking != null) {
            ticking.cancel(false);
        }
        periodMicros = period;
        unitMicros = period / (double) periodUnits;
        lastNanos = fromEpochNanos == 0 ? now : fromEpochNanos;
        seq = 0;
        long current = ++generation;
        ticking = timer.scheduleAtFixedRate(() -> tick(current), firstDelay, period, TimeUnit.MICROSECONDS);
    }

    private synchronized void tick(long ofGeneration) {
        if (ofGeneration == generation) {
            // the tick happens now, its event time; counted before it is published, so before the tester judges it
            long tickedAt = dtron.currentTimeNanos();
            seq = (seq + 1) % 1000;
            double after = units(tickedAt - lastNanos);
            if (Math.abs(after - periodUnits) > TOLERANCE) {
                heldUp("Tick " + seq + " was published " + String.format(Locale.ROOT, "%.3f", after) + " time units"
                        + " after the previous tick or reset: outside its period " + periodUnits + " +/- " + TOLERANCE);
            }
            lastNanos = tickedAt;
            dtron.send(TICK.constructValued(Map.of("seq", seq)), tickedAt);
        }
    }

    private double units(long nanos) {
        return nanos / 1000.0 / unitMicros;
    }

    private static void heldUp(String what) {
        HELD_UP.incrementAndGet();
        LOG.warn("{} (this JVM was held up)", what);
    }
}
