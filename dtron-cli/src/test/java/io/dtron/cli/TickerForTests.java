package io.dtron.cli;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;

/**
 * A ticker system for the command-line tests: ticks every 10 units, or 13 in its "slow" variant; its "broken"
 * variant throws when it starts, its "jammed" variant when it is reset, its "burning" variant at its second tick;
 * its "sticky" variant applies a reset 3 units after it is performed, and reports when it did.
 */
public final class TickerForTests implements Adapter {
    private final long period;
    private final String variant;
    private AdapterContext context;
    private TestClock.Scheduled next;
    private int seq;
    /** How many inputs were performed: the number of the last. */
    private long inputs;

    /** The correct ticker. */
    public TickerForTests() {
        this("correct");
    }

    /** A variant: "correct", "slow", "broken", "jammed" or "burning". */
    public TickerForTests(String variant) {
        this.variant = variant;
        period = switch (variant) {
            case "correct", "jammed", "burning", "sticky" -> 10;
            case "slow", "broken" -> 13;
            default -> throw new IllegalArgumentException("unknown variant '" + variant
                    + "' (correct, slow, broken, jammed, burning, sticky)");
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
    public boolean acknowledgesInputs() {
        return variant.equals("sticky");
    }

    @Override
    public void perform(Event input) {
        if (variant.equals("jammed")) {
            throw new IllegalStateException("the reset button is jammed");
        }
        long ordinal = ++inputs;
        if (variant.equals("sticky")) {
            context.clock().schedule(3 * context.timeUnitMicros(), () -> {
                reset();
                context.inputApplied(ordinal, context.clock().nowMicros());
            });
        } else {
            reset();
        }
    }

    private void reset() {
        next.cancel();
        seq = 0;
        arm();
    }
}
