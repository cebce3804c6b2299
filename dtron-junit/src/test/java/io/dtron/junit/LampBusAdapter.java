package io.dtron.junit;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.RunClock;
import java.util.Map;

/**
 * The system of lamp.xta behind a bus adapter, using nothing of DTRON but its adapter API: every press toggles it,
 * and it shows its new level {@code delayUnits} time units later by the bus's run clock (the model allows 1 to 2).
 */
final class LampBusAdapter implements DtronAdapter {
    static final IDtronChannel PRESS = IDtronChannel.of("press");
    static final IDtronChannel LIGHT = IDtronChannel.of("light", "level");

    private final double delayUnits;
    private Dtron dtron;
    private RunClock.Task pending;
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
    }

    private synchronized void pressed() {
        RunClock clock = dtron.runClock();
        if (!clock.isRunning()) {
            return;
        }
        level = 1 - level;
        int shown = level;
        pending = clock.scheduleAt(clock.nowUnits() + delayUnits, () -> show(shown));
    }

    private void show(int shown) {
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
