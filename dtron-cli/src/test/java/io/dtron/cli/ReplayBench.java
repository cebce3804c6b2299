package io.dtron.cli;

import io.dtron.engine.Event;
import io.dtron.engine.monitor.Monitor;
import io.dtron.engine.monitor.MonitorOptions;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.lang.management.ManagementFactory;
import java.lang.management.ThreadMXBean;
import java.nio.file.Path;

/**
 * The whole replay of {@code dtron monitor --replay} in one JVM, for {@code src/site/markdown/benchmarks.md}: reads
 * a trace of JSON lines with {@link TraceReader} and feeds a new monitor from the initial state, {@code -Druns=N}
 * times (default 20) on this one thread, and prints events per second of the first replay (a cold JIT) and of the
 * best one, wall clock and thread CPU time. Arguments: MODEL TRACE [INTERFACE.trn]; the time unit is 1000 us. Traces
 * come from {@code MonitorBench -Dtrace=DIR}. Run it with the test classpath; see benchmarks.md.
 */
public final class ReplayBench {
    private ReplayBench() {
    }

    public static void main(String[] args) throws Exception {
        Network n = ModelLoader.load(Path.of(args[0]));
        Path trace = Path.of(args[1]);
        TestInterface ti = args.length > 2 ? TestInterface.fromFile(n, Path.of(args[2])) : TestInterface.fromNames(n);
        int runs = Integer.getInteger("runs", 20);
        ThreadMXBean threads = ManagementFactory.getThreadMXBean();
        double first = 0;
        double best = 0;
        double bestCpu = 0;
        long events = 0;
        for (int run = 0; run < runs; run++) {
            Monitor m = Monitor.of(n, ti, MonitorOptions.initial(1000));
            long began = System.nanoTime();
            long cpu = threads.getCurrentThreadCpuTime();
            TraceReader.read(trace, TraceReader.Format.JSON_LINES, new TraceReader.Sink() {
                @Override
                public void event(Event event, long micros, int line) {
                    if (m.observe(event, micros) != null) {
                        throw new IllegalStateException(trace + ":" + line + ": " + m.firstAlarm().explanation());
                    }
                }

                @Override
                public void end(long micros, int line) {
                    m.advanceTo(micros);
                }

                @Override
                public void rejected(int line, String reason) {
                    throw new IllegalStateException(trace + ":" + line + ": " + reason);
                }
            });
            events = m.events();
            double rate = events / ((System.nanoTime() - began) / 1e9);
            bestCpu = Math.max(bestCpu, events / ((threads.getCurrentThreadCpuTime() - cpu) / 1e9));
            first = run == 0 ? rate : first;
            best = Math.max(best, rate);
        }
        System.out.printf("%s: %,d events read and checked: first replay %,.0f events/s, best of %d %,.0f events/s"
                + " (%,.0f per second of the thread's CPU time)%n", trace.getFileName(), events, first, runs, best,
                bestCpu);
    }
}
