package io.dtron.junit;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;

/** The system of lamp.xta: shows its new level 1 time unit after a press, or, {@code late}, after 3. */
final class Lamp implements Adapter {
    private final long delayUnits;
    private AdapterContext context;
    private int level;

    Lamp(boolean late) {
        delayUnits = late ? 3 : 1;
    }

    @Override
    public void start(AdapterContext context) {
        this.context = context;
    }

    @Override
    public void perform(Event input) {
        level = 1 - level;
        int shown = level;
        context.clock().schedule(delayUnits * context.timeUnitMicros(),
                () -> context.report(Event.of("light", "level", shown)));
    }
}
