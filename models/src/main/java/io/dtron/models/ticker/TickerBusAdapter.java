package io.dtron.models.ticker;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import java.time.Instant;
import java.util.Map;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The ticker of {@link TickerSystem} as a bus adapter, for the bundled model {@code io/dtron/models/ticker.xml},
 * using nothing of DTRON but {@code io.dtron.api}. When a run starts ({@link Dtron#RUN_START}, which carries the
 * run's time unit) it publishes {@code tick(seq)} every period, in real time, numbering the ticks from 1; an input
 * {@code reset} restarts the period and the numbering; when the run ends ({@link Dtron#RUN_STOP}) it stops. A period starts at the publish time of the message that
 * starts it, so that the message's own latency does not delay the ticks (exactly so on one host, where the sender
 * and this adapter share the clock). The variants are those of {@link TickerSystem}: {@code correct} (the
 * default) ticks every 10 time units, {@code slow} every 13.
 *
 * <p>The bundled sample end to end, in one command:
 * {@code java -jar dtron.jar ticker.xml --classpath models/target/classes --adapter
 * io.dtron.models.ticker.TickerBusAdapter}.
 */
public final class TickerBusAdapter implements DtronAdapter {
    /** The model's input {@code i_reset}. */
    public static final IDtronChannel RESET = IDtronChannel.of("reset");
    /** The model's output {@code o_tick}, with the tick's number {@code o_tick_seq}. */
    public static final IDtronChannel TICK = IDtronChannel.of("tick", "seq");

    private static final Logger LOG = LoggerFactory.getLogger(TickerBusAdapter.class);

    private final TickerVariant variant;
    private final ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(task -> {
        Thread thread = new Thread(task, "ticker");
        thread.setDaemon(true);
        return thread;
    });
    private final Object lock = new Object();
    private Dtron dtron;
    private long periodMicros;
    private ScheduledFuture<?> ticking;
    private long generation;
    private int seq;

    /** The correct ticker. */
    public TickerBusAdapter() {
        this(TickerVariant.CORRECT.label);
    }

    /**
     * The ticker of the named variant.
     *
     * @throws IllegalArgumentException if {@code variant} is none of {@link TickerSystem#VARIANTS}
     */
    public TickerBusAdapter(String variant) {
        this.variant = TickerVariant.named(variant, TickerBusAdapter.class);
    }

    /** The name of this ticker's variant. */
    public String variant() {
        return variant.label;
    }

    @Override
    public void start(Dtron bus) {
        synchronized (lock) {
            dtron = bus;
        }
        bus.addDtronListener(new DtronListener(Dtron.RUN_START) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                long period = variant.period * (long) message.getVariables().get("timeunit");
                restart(period, period - age(message, period));
            }
        });
        bus.addDtronListener(new DtronListener(Dtron.RUN_STOP) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                pause();
            }
        });
        bus.addDtronListener(new DtronListener(RESET) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                synchronized (lock) {
                    if (periodMicros > 0) {
                        restart(periodMicros, periodMicros - age(message, periodMicros));
                    }
                }
            }
        });
    }

    /** Stops ticking until the next run starts; resets meanwhile are ignored. */
    private void pause() {
        synchronized (lock) {
            generation++;
            periodMicros = 0;
            if (ticking != null) {
                ticking.cancel(false);
            }
        }
    }

    /** Stops ticking; later messages are ignored. */
    @Override
    public void close() {
        synchronized (lock) {
            timer.shutdownNow();
        }
    }

    /**
     * How long ago, in microseconds, a message was published, by the clocks of its sender and of this host: exact
     * on one host. Kept within [0, period / 2], so that the clock of another host that is off does not shift the
     * ticks by more than that.
     */
    private static long age(IDtronChannelValued message, long period) {
        Instant now = Instant.now();
        long nowNanos = now.getEpochSecond() * 1_000_000_000L + now.getNano();
        return Math.max(0, Math.min(period / 2, (nowNanos - message.getPublishTimeNanos()) / 1000));
    }

    private void restart(long period, long firstDelay) {
        synchronized (lock) {
            if (timer.isShutdown()) {
                return;
            }
            if (ticking != null) {
                ticking.cancel(false);
            }
            periodMicros = period;
            seq = 0;
            long current = ++generation;
            ticking = timer.scheduleAtFixedRate(() -> tick(current), firstDelay, period, TimeUnit.MICROSECONDS);
        }
    }

    /** Runs on the timer; a tick of a cancelled period that was already waiting for the lock is dropped. */
    private void tick(long ofGeneration) {
        synchronized (lock) {
            if (ofGeneration != generation) {
                return;
            }
            seq = (seq + 1) % 1000;
            try {
                dtron.send(TICK.constructValued(Map.of("seq", seq)));
            } catch (DtronException e) {
                LOG.warn("Cannot publish tick {}: {}", seq, e.getMessage());
            } catch (IllegalStateException e) {
                ticking.cancel(false);
            }
        }
    }
}
