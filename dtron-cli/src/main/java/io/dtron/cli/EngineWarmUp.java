package io.dtron.cli;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.DelayPolicy;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;

/**
 * Runs the engine's code paths on the model for a moment in virtual time before a real-time run, so that the first
 * inputs of the run are not held up by a cold JVM (class loading and compiling take milliseconds, longer than many
 * windows at 1 ms per time unit). The system under test stands in silent: the warm-up runs end at their first output
 * deadline, which is all they are for, or when the budget is spent (a run is ended at its next input then, and the
 * tester lets time pass after a bounded number of inputs at one instant, so that no run can hold time still).
 */
final class EngineWarmUp {
    private static final long BUDGET_NANOS = 300_000_000L;

    private EngineWarmUp() {
    }

    /** Warms up for at most about 300 ms. */
    static void run(Network network, TestInterface testInterface) {
        long until = System.nanoTime() + BUDGET_NANOS;
        Adapter silent = new Adapter() {
            private AdapterContext context;

            @Override
            public void start(AdapterContext context) {
                this.context = context;
            }

            @Override
            public void perform(Event input) {
                if (System.nanoTime() - until > 0) {
                    context.inconclusive("the warm-up is over");
                }
            }
        };
        for (long seed = 1; System.nanoTime() < until; seed++) {
            TestOptions options = new TestOptions(seed, 1000, 100_000, DelayPolicy.RANDOM, 0, true);
            try {
                new OnlineTester(network, testInterface, silent, options).run();
            } catch (UnsupportedModelException e) {
                return; // the real run says why
            }
        }
    }
}
