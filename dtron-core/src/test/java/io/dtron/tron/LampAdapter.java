package io.dtron.tron;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;

/** {@link TestLamp} as an engine adapter: in-process, on the run's clock. */
final class LampAdapter implements Adapter {
    private final boolean late;
    private TestLamp lamp;

    LampAdapter(boolean late) {
        this.late = late;
    }

    @Override
    public void start(AdapterContext context) {
        lamp = new TestLamp(new TestLamp.Io() {
            @Override
            public long nowMicros() {
                return context.clock().nowMicros();
            }

            @Override
            public TestLamp.Cancel schedule(long micros, Runnable task) {
                return context.clock().schedule(micros, task)::cancel;
            }

            @Override
            public void level(int value) {
                context.report(Event.of("level", "adapLevel", value));
            }
        }, context.timeUnitMicros(), late);
    }

    @Override
    public void perform(Event input) {
        if (input.channel().equals("grasp")) {
            lamp.grasp();
        } else {
            lamp.release();
        }
    }
}
