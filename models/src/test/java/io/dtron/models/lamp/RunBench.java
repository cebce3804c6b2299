package io.dtron.models.lamp;

import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.file.Path;

/**
 * Steps per second of a whole virtual-time run: the shared LightContr against the bundled lamp, a long timeout,
 * several seeds, after warm-up runs; a step is an input applied or an output observed. Counted per second of
 * the running thread's CPU time (a virtual-time run runs on it alone), which a busy machine disturbs less than
 * wall time. For the cost of what every
 * run records (coverage), measured on a commit without it and with it.
 *
 * <p>{@code java -cp ... io.dtron.models.lamp.RunBench [SHARED_MODELS] [ROUNDS]}
 */
public final class RunBench {
    private RunBench() {
    }

    public static void main(String[] args) throws Exception {
        Path shared = Path.of(args.length > 0 ? args[0] : "../shared/models");
        int rounds = args.length > 1 ? Integer.parseInt(args[1]) : 5;
        Network n = ModelLoader.load(shared.resolve("tron/LightContr.xml"));
        TestInterface ti = TestInterface.fromFile(n, shared.resolve("tron/LightContr.trn"));
        long timeout = 200_000;
        java.lang.management.ThreadMXBean threads = java.lang.management.ManagementFactory.getThreadMXBean();
        for (int warm = 0; warm < 3; warm++) {
            new OnlineTester(n, ti, new SmartLamp(), TestOptions.defaults(100 + warm).withTimeout(timeout)).run();
        }
        for (int r = 0; r < rounds; r++) {
            long steps = 0;
            long start = System.nanoTime();
            long cpu = threads.getCurrentThreadCpuTime();
            for (long seed = 1; seed <= 5; seed++) {
                TestResult result = new OnlineTester(n, ti, new SmartLamp(), TestOptions.defaults(seed)
                        .withTimeout(timeout)).run();
                steps += result.inputs() + result.outputs();
            }
            double seconds = (System.nanoTime() - start) / 1e9;
            double cpuSeconds = (threads.getCurrentThreadCpuTime() - cpu) / 1e9;
            System.out.printf(java.util.Locale.ROOT, "round %d: %d steps in %.2f s (%.2f s of CPU): %.0f steps per"
                    + " CPU second%n", r + 1, steps, seconds, cpuSeconds, steps / cpuSeconds);
        }
    }
}
