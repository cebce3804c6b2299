package io.dtron.tron;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;

/**
 * {@link LampAdapter} as {@code dtron run --sut} creates systems under test: a public class with a no-argument
 * constructor (the correct lamp) and one taking the variant ({@code late}).
 */
public final class LampSystem implements Adapter {
    private final LampAdapter lamp;

    /** The correct lamp. */
    public LampSystem() {
        this("correct");
    }

    /** The variant {@code correct} or {@code late}. */
    public LampSystem(String variant) {
        if (!variant.equals("correct") && !variant.equals("late")) {
            throw new IllegalArgumentException("unknown variant '" + variant + "' (correct, late)");
        }
        lamp = new LampAdapter(variant.equals("late"));
    }

    @Override
    public void start(AdapterContext context) {
        lamp.start(context);
    }

    @Override
    public void perform(Event input) {
        lamp.perform(input);
    }
}
