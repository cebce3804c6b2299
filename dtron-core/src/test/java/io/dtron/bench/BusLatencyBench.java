package io.dtron.bench;

import io.dtron.api.DtronOptions;
import io.dtron.bridge.BusBridge;
import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.testadapter.TickerAdapterMain;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.EnumMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.UUID;
import java.util.concurrent.TimeUnit;

/**
 * The latency of the bus under a real-time test: the bundled ticker model, run by DTRON's engine through a
 * {@link BusBridge} in this JVM, against a ticker adapter in another JVM ({@link TickerAdapterMain}, which uses
 * only {@code io.dtron.api}). Prints t2 - t1 (receive minus publish time) of the ticks received: count, min, p50,
 * p99, max.
 *
 * <p>Resets come as early as the model allows (every 25 time units), so the ticker sends two ticks per 25 units.
 * A tick may come 2 units early or late, so with a small time unit one latency spike ends a run FAILED; the bench
 * then starts the next run, until it has the ticks it wants, and says how the runs ended. It first warms both
 * JVMs up for 20 s with a tick every 3 ms and a tolerance of 9 units instead of 2 (the code of a fresh JVM
 * is slow until the JIT has compiled it, which takes thousands of messages), with a bridge of its own, and throws
 * those figures away.
 *
 * <p>Arguments (all optional): the time unit in microseconds (default 1000: a tick every 10 ms), the number
 * of ticks to measure (default 10,000), the ticker model (default
 * {@code ../models/src/main/resources/io/dtron/models/ticker.xml}, from {@code dtron-core}), and the NATS server
 * URLs of a NATS bus (default: none, the embedded JGroups bus), so that the two buses are measured alike, and the
 * secret of a NATS bus (default: none, an insecure bus whose messages carry no codes; with it every message carries
 * a code of it, security.md).
 */
public final class BusLatencyBench {
    private static final Duration WARM_UP = Duration.ofSeconds(20);
    /** The time unit of the warm-up runs: a tick every 3 ms, so that both JVMs compile the bus's code. */
    private static final long WARM_UP_UNIT = 300;
    private static final String TOLERANCE = "const int T = 2;";
    private static final Duration ADAPTERS = Duration.ofSeconds(30);
    private static final long PAUSE_BETWEEN_RUNS_MILLIS = 20;

    private BusLatencyBench() {
    }

    public static void main(String[] args) throws IOException, InterruptedException, ModelException {
        long unit = args.length > 0 ? Long.parseLong(args[0]) : 1000;
        int ticks = args.length > 1 ? Integer.parseInt(args[1]) : 10_000;
        Path modelFile = Path.of(args.length > 2 ? args[2]
                : "../models/src/main/resources/io/dtron/models/ticker.xml");
        List<String> nats = args.length > 3 ? List.of(args[3].split(",")) : List.of();
        Optional<String> secret = args.length > 4 ? Optional.of(args[4]) : Optional.empty();
        Network network = ModelLoader.load(modelFile);
        TestInterface testInterface = TestInterface.fromNames(network);
        String cluster = "bench-" + UUID.randomUUID().toString().substring(0, 8);
        Path adapterLog = Files.createTempFile("bench-adapter", ".log");
        List<String> command = new java.util.ArrayList<>(List.of(Path.of(System.getProperty("java.home"), "bin",
                "java").toString(), "-Xmx256m", "-cp", System.getProperty("java.class.path"),
                TickerAdapterMain.class.getName(), cluster, "bench-adapter", "correct", "2"));
        if (!nats.isEmpty()) {
            command.add(String.join(",", nats));
            command.add(secret.orElse("insecure"));
        }
        Process adapter = new ProcessBuilder(command)
                .redirectErrorStream(true).redirectOutput(adapterLog.toFile()).start();
        try {
            System.out.println((nats.isEmpty() ? "JGroups bus" : "NATS bus " + nats)
                    + (secret.isPresent() ? " with message codes" : "") + ", ticker model, " + unit
                    + " us per time unit (a tick every " + 10 * unit
                    + " us), adapter in another JVM; warming up for " + WARM_UP.toSeconds() + " s with a tick every "
                    + 10 * WARM_UP_UNIT + " us");
            measure(warmUpModel(modelFile), testInterface, options(cluster, nats, secret), WARM_UP_UNIT,
                    System.nanoTime() + WARM_UP.toNanos(), Integer.MAX_VALUE);
            System.out.println("measuring " + ticks + " ticks");
            measure(network, testInterface, options(cluster, nats, secret), unit, Long.MAX_VALUE, ticks);
            if (!adapter.waitFor(30, TimeUnit.SECONDS)) {
                System.out.println("the adapter did not leave; its output:\n" + Files.readString(adapterLog));
            }
        } finally {
            adapter.destroyForcibly();
            Files.deleteIfExists(adapterLog);
        }
    }

    private static DtronOptions.Builder options(String cluster, List<String> nats, Optional<String> secret) {
        DtronOptions.Builder options = DtronOptions.builder().clusterName(cluster);
        if (nats.isEmpty()) {
            return options;
        }
        secret.ifPresentOrElse(options::secret, () -> options.insecure(true));
        return options.natsServers(nats);
    }

    /**
     * The ticker with a tolerance of 9 units instead of 2, so that warm-up runs with a tick every millisecond do
     * not end at the first late tick of a cold JVM.
     */
    private static Network warmUpModel(Path modelFile) throws IOException, ModelException {
        String text = Files.readString(modelFile);
        if (!text.contains(TOLERANCE)) {
            throw new IllegalStateException(modelFile + " no longer declares '" + TOLERANCE + "'");
        }
        return ModelLoader.load("ticker-warm-up.xml", text.replace(TOLERANCE, "const int T = 9;"));
    }

    /** Runs the model again and again on a bridge of its own until the deadline or until it has the ticks. */
    private static void measure(Network network, TestInterface testInterface, DtronOptions.Builder options, long unit,
                                long deadlineNanos, int ticks) throws InterruptedException {
        try (BusBridge bridge = BusBridge.connect(testInterface, options)) {
            if (!bridge.run().awaitAdapters(1, ADAPTERS)) {
                throw new IllegalStateException("the adapter did not join within " + ADAPTERS);
            }
            Map<Verdict, Integer> verdicts = new EnumMap<>(Verdict.class);
            int longest = 0;
            String firstFailure = null;
            long start = System.nanoTime();
            long seed = 1;
            while (System.nanoTime() < deadlineNanos && bridge.run().outputLatency().count() < ticks) {
                long left = ticks - bridge.run().outputLatency().count();
                long units = Math.min(2_000_000_000L, Math.max(25, left / 2 * 25));
                TestResult result = new OnlineTester(network, testInterface, bridge,
                        new TestOptions(seed++, unit, units, DelayPolicy.EAGER, 0, false)).run();
                verdicts.merge(result.verdict(), 1, Integer::sum);
                longest = Math.max(longest, result.outputs());
                if (result.verdict() != Verdict.PASSED && firstFailure == null) {
                    firstFailure = result.verdict() + ": " + result.explanation();
                }
                Thread.sleep(PAUSE_BETWEEN_RUNS_MILLIS);
            }
            System.out.printf("%.1f s, runs %s, most ticks in one run %d%n", (System.nanoTime() - start) / 1e9,
                    verdicts, longest);
            if (firstFailure != null) {
                System.out.println("first run that did not pass: " + firstFailure);
            }
            System.out.println("latency t2 - t1 of ticks: " + bridge.run().outputLatency());
            System.out.println("latency t2 - t1 of resets back from the bus: " + bridge.run().inputLatency());
            System.out.println("bus: " + bridge.run().stats());
        }
    }
}
