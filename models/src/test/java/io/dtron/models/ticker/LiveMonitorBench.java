package io.dtron.models.ticker;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.cli.DtronCommand;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;

/**
 * What live monitoring adds to the event path, as a plain main (not a test): a producer publishes the ticker's ticks
 * on a JGroups bus on loopback, one every 20 ms (the model's period at 2 ms per time unit), and a consumer in the same
 * JVM receives them. Three phases of N ticks each: without a monitor, with a passive monitor ({@code dtron monitor
 * --cluster}) on the bus, and with a shield ({@code --shield tick}), whose consumer listens to {@code tick_shielded}.
 * Prints the p50, p99 and max of each tick's latency (receive minus publish time) without and with the passive
 * monitor, and the shield's added latency (the shielded copy's receive time minus the original's, at the same
 * consumer). Figures go in {@code src/site/markdown/benchmarks.md}.
 *
 * <pre>java -cp ... io.dtron.models.ticker.LiveMonitorBench [N]   (default 500)</pre>
 */
public final class LiveMonitorBench {
    private static final String MODEL = "src/main/resources/io/dtron/models/ticker.xml";
    private static final IDtronChannel TICK = IDtronChannel.of("tick", "seq");
    private static final long PERIOD_NANOS = 20_000_000L;

    private LiveMonitorBench() {
    }

    public static void main(String[] args) throws Exception {
        int n = args.length > 0 ? Integer.parseInt(args[0]) : 500;
        if (n < 10 || n > 999) {
            throw new IllegalArgumentException("N is 10 to 999 ticks (the tick's number wraps at 1000)");
        }
        long[] bare = phase(n, null);
        long[] passive = phase(n, "passive");
        long[] shielded = phase(n, "shield");
        System.out.println("ticks per phase: " + n + ", one every " + PERIOD_NANOS / 1_000_000 + " ms, JGroups on"
                + " loopback, producer, consumer and monitor in one JVM; load average "
                + java.nio.file.Files.readString(java.nio.file.Path.of("/proc/loadavg")).strip()
                + " (the monitors' alarms after the last tick: the ticker stopped)");
        System.out.println("latency without a monitor:     " + summary(bare));
        System.out.println("latency with a passive monitor: " + summary(passive));
        System.out.println("added by the shield:           " + summary(shielded));
    }

    /** One phase: the latencies (or, with a shield, the added latencies) of the ticks, in microseconds. */
    private static long[] phase(int n, String monitor) throws Exception {
        String cluster = "bench-" + UUID.randomUUID().toString().substring(0, 8);
        DtronOptions.Builder options = DtronOptions.builder().clusterName(cluster)
                .bindAddress(InetAddress.getLoopbackAddress());
        Map<Integer, Long> direct = new ConcurrentHashMap<>();
        Map<Integer, Long> latency = new ConcurrentHashMap<>();
        Map<Integer, Long> viaShield = new ConcurrentHashMap<>();
        try (Dtron consumer = Dtron.connect(options.build()); Dtron producer = Dtron.connect(options.build())) {
            consumer.addDtronListener(new DtronListener(TICK) {
                @Override
                public void messageReceived(IDtronChannelValued m) {
                    direct.put(m.getVariables().get("seq"), m.getReceiveTimeNanos());
                    latency.put(m.getVariables().get("seq"), m.getReceiveTimeNanos() - m.getPublishTimeNanos());
                }
            });
            consumer.addDtronListener(new DtronListener(IDtronChannel.of("tick_shielded", "seq")) {
                @Override
                public void messageReceived(IDtronChannelValued m) {
                    viaShield.put(m.getVariables().get("seq"), m.getReceiveTimeNanos());
                }
            });
            CompletableFuture<Integer> watch = null;
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            if (monitor != null) {
                List<String> cmd = new ArrayList<>(List.of("monitor", MODEL, "--cluster", cluster, "--timeunit",
                        "2000", "--duration", String.valueOf(n * PERIOD_NANOS / 1_000_000_000L + 2)));
                if (monitor.equals("shield")) {
                    cmd.addAll(List.of("--shield", "tick"));
                }
                watch = CompletableFuture.supplyAsync(() -> DtronCommand.run(cmd.toArray(String[]::new),
                        new PrintWriter(out, true), new PrintWriter(err, true)));
                if (!producer.awaitMembers(3, java.time.Duration.ofSeconds(60))) {
                    throw new IllegalStateException("the monitor did not join the bus");
                }
            }
            // each tick stamped at its period's time, so that the ticks keep the model's timing however late this
            // thread wakes up (the latencies are from publish to receive times)
            long next = System.nanoTime();
            long stamp = producer.currentTimeNanos();
            for (int seq = 1; seq <= n; seq++) {
                next += PERIOD_NANOS;
                stamp += PERIOD_NANOS;
                LockSupport.parkNanos(next - System.nanoTime());
                producer.send(TICK.constructValued(Map.of("seq", seq)), stamp);
            }
            LockSupport.parkNanos(500_000_000L);
            if (watch != null) {
                int exit = watch.get(5, TimeUnit.MINUTES);
                System.out.println(monitor + " monitor, exit " + exit + ": " + out.toString().lines()
                        .reduce((a, b) -> b).orElse("") + err.toString().strip());
            }
        }
        List<Long> micros = new ArrayList<>();
        for (int seq = 1; seq <= n; seq++) {
            if ("shield".equals(monitor)) {
                if (viaShield.containsKey(seq) && direct.containsKey(seq)) {
                    micros.add((viaShield.get(seq) - direct.get(seq)) / 1000);
                }
            } else if (latency.containsKey(seq)) {
                micros.add(latency.get(seq) / 1000);
            }
        }
        return micros.stream().mapToLong(Long::longValue).toArray();
    }

    private static String summary(long[] micros) {
        long[] sorted = micros.clone();
        Arrays.sort(sorted);
        if (sorted.length == 0) {
            return "no samples";
        }
        return String.format(Locale.ROOT, "%d samples, p50 %d us, p99 %d us, max %d us", sorted.length,
                sorted[sorted.length / 2], sorted[Math.min(sorted.length - 1, (int) Math.ceil(sorted.length * 0.99)
                        - 1)], sorted[sorted.length - 1]);
    }
}
