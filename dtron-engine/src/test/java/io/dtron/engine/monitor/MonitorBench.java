package io.dtron.engine.monitor;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.lang.management.GarbageCollectorMXBean;
import java.lang.management.ManagementFactory;
import java.lang.management.ThreadMXBean;
import java.io.BufferedWriter;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

/**
 * Replay throughput of the monitor, for {@code src/site/markdown/benchmarks.md}: records a long run of each model
 * against its own implementation part in virtual time ({@code -Devents=N}, default 200,000 events, or as many as 500,000 time units
 * give), then replays it
 * {@code -Druns=N} times (default 5), each with a new monitor from the initial state, on this one thread, and prints
 * events per second of the first replay (a cold JIT) and of the best one. Events are built before the clock starts:
 * this measures the engine, not the reading of a file. It also prints the best rate per second of this thread's CPU
 * time, which other processes on a busy machine disturb less than the wall clock. Run it with the test classpath;
 * see benchmarks.md. With {@code -Dtrace=DIR} it also writes each run to {@code DIR} as JSON lines, for timing {@code
 * dtron monitor --replay} on it; {@code -Dmodel=LightContr} or {@code streetlight} runs one model only.
 */
public final class MonitorBench {
    /** The tester's delay policy in the recorded runs ({@code -Dpolicy=eager}; default random). */
    private static final DelayPolicy POLICY = DelayPolicy.valueOf(System.getProperty("policy", "random")
            .toUpperCase(java.util.Locale.ROOT).replace('-', '_'));

    private MonitorBench() {
    }

    public static void main(String[] args) throws Exception {
        Path shared = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
        int wanted = Integer.getInteger("events", 200_000);
        int runs = Integer.getInteger("runs", 5);
        String only = System.getProperty("model", "");
        if (!only.equals("streetlight")) {
            Network lamp = ModelLoader.load(shared.resolve("tron/LightContr.xml"));
            bench("LightContr", lamp, TestInterface.fromFile(lamp, shared.resolve("tron/LightContr.trn")), wanted, runs);
        }
        if (!only.equals("LightContr")) {
            Network street = ModelLoader.load(Path.of("../models/src/main/resources/io/dtron/models/streetlight/"
                    + "streetlight.xml"));
            bench("streetlight", street, TestInterface.fromNames(street), wanted, runs);
        }
    }

    /** The run as a trace of JSON lines, as {@code dtron run --trace} writes its events, for {@code --replay}. */
    private static void write(Path file, Event[] e, long[] t, List<Boolean> inputs) throws IOException {
        try (BufferedWriter out = Files.newBufferedWriter(file, StandardCharsets.UTF_8)) {
            out.write("{\"kind\":\"start\",\"timeunit_us\":1000}\n");
            for (int i = 0; i < e.length; i++) {
                StringBuilder values = new StringBuilder();
                e[i].values().forEach((k, v) -> values.append(values.length() == 0 ? "" : ",").append('"').append(k)
                        .append("\":").append(v));
                out.write("{\"kind\":\"" + (inputs.get(i) ? "input" : "output") + "\",\"t_us\":" + t[i]
                        + ",\"channel\":\"" + e[i].channel() + "\",\"values\":{" + values + "}}\n");
            }
        }
    }

    private static long gcMillis() {
        long ms = 0;
        for (GarbageCollectorMXBean gc : ManagementFactory.getGarbageCollectorMXBeans()) {
            ms += Math.max(0, gc.getCollectionTime());
        }
        return ms;
    }

    private static void bench(String name, Network n, TestInterface ti, int wanted, int runs) throws IOException {
        List<Event> events = new ArrayList<>();
        List<Long> times = new ArrayList<>();
        List<Boolean> inputs = new ArrayList<>();
        long timeout = 10_000;
        long offset = 0;
        // runs of one seed after another would not connect: one run, long enough
        // at 1000 ticks per unit a clock counts to 536,870 units: the run stops before
        while (events.size() < wanted && timeout <= 500_000) {
            events.clear();
            times.clear();
            inputs.clear();
            TestOptions o = new TestOptions(1, 1000, timeout, POLICY, 0, true);
            OnlineTester tester = new OnlineTester(n, ti, new ModelSystem(n, ti, 7919), o);
            tester.addListener(new TestListener() {
                @Override
                public void inputApplied(Event input, long micros) {
                    events.add(input);
                    times.add(micros + offset);
                    inputs.add(true);
                }

                @Override
                public void outputObserved(Event output, long micros) {
                    events.add(output);
                    times.add(micros + offset);
                    inputs.add(false);
                }
            });
            TestResult r = tester.run();
            if (r.verdict() != Verdict.PASSED) {
                throw new IllegalStateException(name + ": " + r.explanation());
            }
            timeout = timeout == 500_000 ? timeout + 1
                    : Math.min(500_000, Math.max(2 * timeout, timeout * wanted / Math.max(1, events.size()) + 1000));
        }
        Event[] e = events.toArray(Event[]::new);
        long[] t = times.stream().mapToLong(Long::longValue).toArray();
        String trace = System.getProperty("trace");
        if (trace != null) {
            write(Path.of(trace, name + "-" + POLICY.name().toLowerCase(java.util.Locale.ROOT) + ".jsonl"), e, t, inputs);
        }
        double first = 0;
        double best = 0;
        double bestCpu = 0;
        ThreadMXBean threads = ManagementFactory.getThreadMXBean();
        long gcBefore = gcMillis();
        for (int run = 0; run < runs; run++) {
            Monitor m = Monitor.of(n, ti, MonitorOptions.initial(1000));
            long began = System.nanoTime();
            long cpu = threads.getCurrentThreadCpuTime();
            for (int i = 0; i < e.length; i++) {
                if (m.observe(e[i], t[i]) != null) {
                    throw new IllegalStateException(name + ": " + m.firstAlarm().explanation());
                }
            }
            double rate = e.length / ((System.nanoTime() - began) / 1e9);
            bestCpu = Math.max(bestCpu, e.length / ((threads.getCurrentThreadCpuTime() - cpu) / 1e9));
            first = run == 0 ? rate : first;
            best = Math.max(best, rate);
        }
        long gc = gcMillis() - gcBefore;
        System.out.printf("%-12s %-6s %,9d events over %,d time units: first replay %,12.0f events/s, best of %d %,12.0f"
                + " events/s (%,.0f per second of the thread's CPU time); %,d ms collecting garbage in the %d replays%n",
                name, POLICY.name().toLowerCase(java.util.Locale.ROOT), e.length, t[t.length - 1] / 1000, first, runs,
                best, bestCpu, gc, runs);
    }
}
