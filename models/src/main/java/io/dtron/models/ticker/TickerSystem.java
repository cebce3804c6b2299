package io.dtron.models.ticker;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import java.util.List;

/**
 * A ticker to test against the bundled model {@code io/dtron/models/ticker.xml}: it emits output {@code tick}
 * with variable {@code seq} periodically and restarts on input {@code reset}.
 *
 * <p>The model allows a tick every P +/- T = 10 +/- 2 time units after the previous tick or reset, each carrying
 * the previous {@code seq} plus one modulo 1000, where {@code seq} is 0 at the start and after a reset (so the
 * first tick carries 1). Variants:
 * <ul>
 *   <li>{@code correct} (the default): ticks exactly every 10 units, as the model wants;</li>
 *   <li>{@code slow}: ticks every 13 units, later than the 12 the model allows.</li>
 * </ul>
 * A reset at the instant a tick is due either comes after the tick (both are observed) or cancels it (the next
 * tick comes a full period after the reset); the model allows both orders.
 */
public final class TickerSystem implements Adapter {

    /** The names of the variants, the correct ticker first. */
    public static final List<String> VARIANTS = TickerVariant.LABELS;

    private final TickerVariant variant;
    private AdapterContext context;
    private TestClock.Scheduled nextTick;
    private int seq;

    /** The correct ticker. */
    public TickerSystem() {
        this(TickerVariant.CORRECT.label);
    }

    /**
     * The ticker of the named variant.
     *
     * @throws IllegalArgumentException if {@code variant} is none of {@link #VARIANTS}
     */
    public TickerSystem(String variant) {
        this.variant = TickerVariant.named(variant, TickerSystem.class);
    }

    /** The name of this ticker's variant. */
    public String variant() {
        return variant.label;
    }

    @Override
    public void start(AdapterContext context) {
        this.context = context;
        scheduleTick();
    }

    @Override
    public void perform(Event input) {
        if (!input.channel().equals("reset")) {
            throw new IllegalArgumentException("the ticker has no input '" + input.channel() + "'; its input is reset");
        }
        nextTick.cancel();
        seq = 0;
        scheduleTick();
    }

    @Override
    public void stop() {
        if (nextTick != null) {
            nextTick.cancel();
        }
    }

    private void scheduleTick() {
        nextTick = context.clock().schedule(variant.period * context.timeUnitMicros(), this::tick);
    }

    private void tick() {
        seq = (seq + 1) % 1000;
        context.report(Event.of("tick", "seq", seq));
        scheduleTick();
    }
}
