package io.dtron.cli;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;

/**
 * The lamp of {@code zeno-lamp.xta}, in process: answers the first grasp with level 2 time units later, or, in its
 * "silent" variant, never.
 */
public final class ZenoLamp implements Adapter {
    private final boolean silent;
    private AdapterContext context;
    private boolean grasped;

    /** The correct lamp. */
    public ZenoLamp() {
        this("correct");
    }

    /** A variant: "correct" or "silent". */
    public ZenoLamp(String variant) {
        silent = switch (variant) {
            case "correct" -> false;
            case "silent" -> true;
            default -> throw new IllegalArgumentException("unknown variant '" + variant + "' (correct, silent)");
        };
    }

    @Override
    public void start(AdapterContext context) {
        this.context = context;
    }

    @Override
    public void perform(Event input) {
        if (silent || grasped || !input.channel().equals("grasp")) {
            return;
        }
        grasped = true;
        context.clock().schedule(2 * context.timeUnitMicros(), () -> context.report(Event.of("level")));
    }
}
