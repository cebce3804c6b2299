package io.dtron.cli;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;

/** A ticker system for the command-line tests: ticks every 10 units, or 13 in its "slow" variant. */
public final class TickerForTests implements Adapter {
    private final long period;
    private AdapterContext context;
    private TestClock.Scheduled next;
    private int seq;

    /** The correct ticker. */
    public TickerForTests() {
        this("correct");
    }

    /** A variant: "correct" or "slow". */
    public TickerForTests(String variant) {
        period = switch (variant) {
            case "correct" -> 10;
            case "slow" -> 13;
            default -> throw new IllegalArgumentException("unknown variant '" + variant + "' (correct, slow)");
        };
    }

    @Override
    public void start(AdapterContext context) {
        this.context = context;
        arm();
    }

    private void arm() {
        next = context.clock().schedule(period * context.timeUnitMicros(), () -> {
            seq = (seq + 1) % 1000;
            context.report(Event.of("tick", "seq", seq));
            arm();
        });
    }

    @Override
    public void perform(Event input) {
        next.cancel();
        seq = 0;
        arm();
    }
}
