package io.dtron.models.ticker;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.RunClock;
import java.util.Map;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The ticker of {@link TickerSystem} as a bus adapter, for the bundled model {@code io/dtron/models/ticker.xml},
 * using nothing of DTRON but {@code io.dtron.api}. It keeps the tester's time with the bus's {@link RunClock}: from
 * time 0 of a run it publishes {@code tick(seq)} one period after the previous tick (or the start), numbering the
 * ticks from 1; an input {@code reset} restarts the period and the numbering from when the reset was applied (its
 * listener returning is the acknowledgement the tester places it by); the run's end stops it. Because the ticks are
 * scheduled at run times, a start message that reaches this adapter late, or a clock of this host that is off, does
 * not move them. The variants are those of {@link TickerSystem}: {@code correct} (the default) ticks every 10 time
 * units, {@code slow} every 13.
 *
 * <p>It checks its own schedule: a tick that this adapter itself published more than {@value #TOLERANCE} time
 * units away from its period after the previous tick or reset (its JVM was held up) is logged as a warning, so
 * that a FAILED verdict can be told apart: the ticker was late, or the verdict was wrong.
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
    /** The model's tolerance T either side of the period, in time units. */
    static final int TOLERANCE = 2;

    private static final Logger LOG = LoggerFactory.getLogger(TickerBusAdapter.class);

    private final TickerVariant variant;
    private Dtron dtron;
    private RunClock.Task next;
    private long generation;
    private int seq;
    /** The run time, in units, of the last tick or reset: the next tick is due a period later. */
    private double last;

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
    public synchronized void start(Dtron bus) {
        dtron = bus;
        bus.declareOutputs(TICK);
        bus.addDtronListener(new DtronListener(Dtron.RUN_START) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                restart(0);
            }
        });
        bus.addDtronListener(new DtronListener(Dtron.RUN_STOP) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                overdue(message);
            }
        });
        bus.addDtronListener(new DtronListener(RESET) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                RunClock clock = getDtron().runClock();
                if (clock.isRunning()) {
                    restart(clock.nowUnits());
                }
            }
        });
    }

    /** Stops ticking; later messages are ignored. */
    @Override
    public synchronized void close() {
        generation++;
        if (next != null) {
            next.cancel();
        }
    }

    /** Numbers the ticks from 1 again, the next one due a period after run time {@code fromUnits}. */
    private synchronized void restart(double fromUnits) {
        if (next != null) {
            next.cancel();
        }
        seq = 0;
        last = fromUnits;
        schedule(++generation);
    }

    private void schedule(long ofGeneration) {
        next = dtron.runClock().scheduleAt(last + variant.period, () -> tick(ofGeneration));
    }

    /**
     * Runs on the run clock's thread; a tick of a restarted period that was already waiting is dropped. The tick is
     * published with the time it happened as its event time.
     */
    private synchronized void tick(long ofGeneration) {
        if (ofGeneration != generation) {
            return;
        }
        // the tick happens now; publishing it takes a moment more (much more, the first time in a fresh JVM)
        long tickedAt = dtron.currentTimeNanos();
        seq = (seq + 1) % 1000;
        IDtronChannelValued sent;
        try {
            sent = dtron.send(TICK.constructValued(Map.of("seq", seq)), tickedAt);
        } catch (DtronException e) {
            LOG.warn("Cannot publish tick {}: {}", seq, e.getMessage());
            return;
        } catch (IllegalStateException e) {
            return; // closed
        }
        RunClock clock = dtron.runClock();
        double at = clock.runNanosOf(sent) / (clock.timeUnitMicros() * 1000.0);
        double after = at - last;
        if (Math.abs(after - variant.period) > TOLERANCE) {
            LOG.warn("Tick {} at t={} by this adapter's run clock (due at t={}), {} time units after the previous"
                    + " tick or reset: outside its period {} +/- {} (this JVM was held up)", seq, units(at),
                    units(last + variant.period), units(after), variant.period, TOLERANCE);
        }
        last = at;
        schedule(ofGeneration);
    }

    /**
     * At the end of a run: warns when the next tick was due (outside its tolerance) before the run ended but never
     * ran, as when this JVM was held up so long that the tester gave up waiting for it.
     */
    private synchronized void overdue(IDtronChannelValued stop) {
        RunClock clock = dtron.runClock();
        double end = clock.runNanosOf(stop) / (clock.timeUnitMicros() * 1000.0);
        double due = last + variant.period;
        if (due + TOLERANCE < end) {
            LOG.warn("Tick {} was due at t={} by this adapter's run clock and had not been published when the run"
                    + " ended at t={} (this JVM was held up)", seq + 1, units(due), units(end));
        }
    }

    private static String units(double value) {
        return String.format(java.util.Locale.ROOT, "%.3f", value);
    }
}
