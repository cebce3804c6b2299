package io.dtron.testadapter;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import java.time.Instant;
import java.util.Map;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * A ticker on the bus for the ticker model, using only {@code io.dtron.api}: from the start of a run it publishes
 * {@code tick(seq)} every 10 time units ({@code slow}: 13), and restarts on {@code reset}, until the run stops;
 * the first period counts from the run's time 0 (the event time of its start), and a period after a reset from when
 * this adapter applied the reset, as it acknowledges it (counting from the reset's publish time would tick early by
 * the reset's way here: a false FAILED when that way takes more than the model's tolerance).
 */
public final class BusTicker implements DtronAdapter {
    private static final IDtronChannel RESET = IDtronChannel.of("reset");
    private static final IDtronChannel TICK = IDtronChannel.of("tick", "seq");

    private final int periodUnits;
    private final ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(task -> {
        Thread thread = new Thread(task, "bus-ticker");
        thread.setDaemon(true);
        return thread;
    });
    private final AtomicInteger resets = new AtomicInteger();
    private Dtron dtron;
    private long periodMicros;
    private ScheduledFuture<?> ticking;
    private long generation;
    private int seq;

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
                stop();
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

    /** Stops ticking until the next run starts. */
    public synchronized void stop() {
        generation++;
        if (ticking != null) {
            ticking.cancel(false);
        }
        periodMicros = 0;
    }

    /** Returns how many resets arrived. */
    public int resets() {
        return resets.get();
    }

    @Override
    public synchronized void close() {
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
        Instant now = Instant.now();
        long age = fromEpochNanos == 0 ? 0
                : (now.getEpochSecond() * 1_000_000_000L + now.getNano() - fromEpochNanos) / 1000;
        long firstDelay = period - Math.max(0, Math.min(period / 2, age));
        if (ticking != null) {
            ticking.cancel(false);
        }
        periodMicros = period;
        seq = 0;
        long current = ++generation;
        ticking = timer.scheduleAtFixedRate(() -> tick(current), firstDelay, period, TimeUnit.MICROSECONDS);
    }

    private synchronized void tick(long ofGeneration) {
        if (ofGeneration == generation) {
            seq = (seq + 1) % 1000;
            dtron.send(TICK.constructValued(Map.of("seq", seq)));
        }
    }
}
