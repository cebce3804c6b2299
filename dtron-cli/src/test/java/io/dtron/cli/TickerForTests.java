package io.dtron.cli;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;

/**
 * A ticker system for the command-line tests: ticks every 10 units, or 13 in its "slow" variant; its "broken"
 * variant throws when it starts.
 */
public final class TickerForTests implements Adapter {
    private final long period;
    private final boolean broken;
    private AdapterContext context;
    private TestClock.Scheduled next;
    private int seq;

    /** The correct ticker. */
    public TickerForTests() {
        this("correct");
    }

    /** A variant: "correct", "slow" or "broken". */
    public TickerForTests(String variant) {
        broken = variant.equals("broken");
        period = switch (variant) {
            case "correct" -> 10;
            case "slow", "broken" -> 13;
            default -> throw new IllegalArgumentException("unknown variant '" + variant + "' (correct, slow, broken)");
        };
    }

    @Override
    public void start(AdapterContext context) {
        if (broken) {
            throw new IllegalStateException("the ticker is unplugged");
        }
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
