package io.dtron.testadapter;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.RunClock;
import java.util.Map;

/**
 * A ticker on the bus for the ticker model that counts the tester's time, using only {@code io.dtron.api}: from
 * time 0 of a run it publishes {@code tick(seq)} at run times 10, 20, 30, ... units ({@code slow}: 13), and a
 * {@code reset} restarts the period and the numbering at the reset's own run time; the run clock stops it with the
 * run. Unlike {@link BusTicker} it is right when its clock differs from the tester's.
 */
public final class RunClockTicker implements DtronAdapter {
    private static final IDtronChannel RESET = IDtronChannel.of("reset");
    private static final IDtronChannel TICK = IDtronChannel.of("tick", "seq");

    private final int periodUnits;
    private Dtron dtron;
    private RunClock.Task ticking;
    private long generation;
    private int seq;

    /** The correct ticker. */
    public RunClockTicker() {
        this("correct");
    }

    /** A variant: "correct" or "slow". */
    public RunClockTicker(String variant) {
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
                restart(0);
            }
        });
        bus.addDtronListener(new DtronListener(RESET) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                RunClock clock = getDtron().runClock();
                if (clock.isRunning()) {
                    restart(clock.runNanosOf(message) / (clock.timeUnitMicros() * 1_000.0));
                }
            }
        });
    }

    /** Ticks every period from run time {@code fromUnits} on, numbering from 1. */
    private synchronized void restart(double fromUnits) {
        if (ticking != null) {
            ticking.cancel();
        }
        seq = 0;
        long current = ++generation;
        ticking = dtron.runClock().scheduleAtFixedRate(fromUnits + periodUnits, periodUnits, () -> tick(current));
    }

    private synchronized void tick(long ofGeneration) {
        if (ofGeneration == generation) {
            seq = (seq + 1) % 1000;
            dtron.send(TICK.constructValued(Map.of("seq", seq)));
        }
    }
}
