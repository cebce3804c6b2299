package io.dtron.cli;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;

/**
 * A ticker system for the command-line tests: ticks every 10 units, or 13 in its "slow" variant; its "broken"
 * variant throws when it starts, its "jammed" variant when it is reset, its "burning" variant at its second tick.
 */
public final class TickerForTests implements Adapter {
    private final long period;
    private final String variant;
    private AdapterContext context;
    private TestClock.Scheduled next;
    private int seq;

    /** The correct ticker. */
    public TickerForTests() {
        this("correct");
    }

    /** A variant: "correct", "slow", "broken", "jammed" or "burning". */
    public TickerForTests(String variant) {
        this.variant = variant;
        period = switch (variant) {
            case "correct", "jammed", "burning" -> 10;
            case "slow", "broken" -> 13;
            default -> throw new IllegalArgumentException("unknown variant '" + variant
                    + "' (correct, slow, broken, jammed, burning)");
        };
    }

    @Override
    public void start(AdapterContext context) {
        if (variant.equals("broken")) {
            throw new IllegalStateException("the ticker is unplugged");
        }
        this.context = context;
        arm();
    }

    private void arm() {
        next = context.clock().schedule(period * context.timeUnitMicros(), () -> {
            seq = (seq + 1) % 1000;
            if (variant.equals("burning") && seq == 2) {
                throw new IllegalStateException("the ticker burnt out");
            }
            context.report(Event.of("tick", "seq", seq));
            arm();
        });
    }

    @Override
    public void perform(Event input) {
        if (variant.equals("jammed")) {
            throw new IllegalStateException("the reset button is jammed");
        }
        next.cancel();
        seq = 0;
        arm();
    }
}
