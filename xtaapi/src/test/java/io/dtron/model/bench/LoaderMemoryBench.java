package io.dtron.model.bench;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.io.IOException;
import java.lang.management.ManagementFactory;
import java.lang.ref.Reference;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.function.IntFunction;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * How much heap the model loader needs: generates large models ({@link GeneratedModels#editorFile}, many
 * templates as the Uppaal editor writes them, and {@link GeneratedModels#largeDeclarations}, one big
 * declarations section), writes each to a temporary file and loads it ({@link ModelLoader#load(Path)}, as
 * {@code dtron check} does) in child JVMs with the default garbage collector:
 *
 * <ul>
 *   <li>one load with the largest heap ({@code -Dbench.maxHeapMb}, default 4096) gives the load time and the
 *   heap the loaded {@link Network} retains (heap in use after a full GC, minus the same before the load);</li>
 *   <li>bisection over {@code -Xmx} finds the smallest heap with which the load succeeds (to within 3%): the
 *   peak the loader needs.</li>
 * </ul>
 *
 * <p>Arguments: the model sizes in MB (default 10 50). A size whose load does not fit in the largest heap is
 * reported as such. Run it from a plain {@code java} command with the classpath of xtaapi's tests (the
 * children reuse it); see the loader section of {@code src/site/markdown/benchmarks.md}. With
 * {@code child FILE} it is the child: it loads FILE once and prints one line of figures.
 */
public final class LoaderMemoryBench {
    private static final long MB = 1 << 20;
    private static final Pattern FIGURES = Pattern.compile(
            "processes=(\\d+) edges=(\\d+) millis=(\\d+) retained=(\\d+)");
    /** Bisection stops when the bounds are this close, relative to the upper one. */
    private static final double PRECISION = 0.03;

    private LoaderMemoryBench() {
    }

    public static void main(String[] args) throws Exception {
        if (args.length == 2 && args[0].equals("child")) {
            child(Path.of(args[1]));
            return;
        }
        List<Integer> sizes = new ArrayList<>();
        for (String a : args) {
            sizes.add(Integer.parseInt(a));
        }
        if (sizes.isEmpty()) {
            sizes.addAll(List.of(10, 50));
        }
        long maxHeapMb = Long.getLong("bench.maxHeapMb", 4096);
        System.out.printf("machine: %d cores, Java %s, %s; largest heap tried %d MB%n",
                Runtime.getRuntime().availableProcessors(), System.getProperty("java.version"),
                System.getProperty("os.name"), maxHeapMb);
        System.out.println("| model | file | processes | edges | load time | retained heap | smallest -Xmx that loads |");
        System.out.println("|---|---|---|---|---|---|---|");
        for (int size : sizes) {
            measure("templates", size, GeneratedModels::editorFile, maxHeapMb);
            measure("declarations", size, GeneratedModels::largeDeclarations, maxHeapMb);
        }
    }

    private static void measure(String kind, int sizeMb, IntFunction<String> generator, long maxHeapMb)
            throws IOException, InterruptedException {
        Path file = Files.createTempFile("loader-bench-" + kind + "-", ".xml");
        try {
            Files.writeString(file, generator.apply((int) (sizeMb * MB)), StandardCharsets.UTF_8);
            double fileMb = Files.size(file) / (double) MB;
            Trial full = load(file, maxHeapMb, 0);
            if (!full.loaded()) {
                System.out.printf("| %s | %.1f MB | | | | | more than %d MB |%n", kind, fileMb, maxHeapMb);
                return;
            }
            long lo = Math.max(8, full.retained() / MB);
            long hi = maxHeapMb;
            long patience = Math.max(60_000, 20 * full.millis());
            while (hi - lo > Math.max(2, hi * PRECISION)) {
                long mid = (lo + hi) / 2;
                if (load(file, mid, patience).loaded()) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            double retainedMb = full.retained() / (double) MB;
            System.out.printf("| %s | %.1f MB | %,d | %,d | %.1f s | %.0f MB (%.1f x file) | %d MB (%.1f x file) |%n",
                    kind, fileMb, full.processes(), full.edges(), full.millis() / 1000.0, retainedMb,
                    retainedMb / fileMb, hi, hi / fileMb);
        } finally {
            Files.deleteIfExists(file);
        }
    }

    /** What one child JVM reported; {@code loaded} is false when it ran out of heap or time. */
    private record Trial(boolean loaded, int processes, int edges, long millis, long retained) {
    }

    /** Loads {@code file} in a child JVM with {@code -Xmx heapMb}; {@code patienceMillis} 0 waits for ever. */
    private static Trial load(Path file, long heapMb, long patienceMillis) throws IOException, InterruptedException {
        Path log = Files.createTempFile("loader-bench-", ".log");
        try {
            Process child = new ProcessBuilder(Path.of(System.getProperty("java.home"), "bin", "java").toString(),
                    "-Xmx" + heapMb + "m", "-cp", System.getProperty("java.class.path"),
                    LoaderMemoryBench.class.getName(), "child", file.toString())
                    .redirectErrorStream(true).redirectOutput(log.toFile()).start();
            boolean ended = patienceMillis == 0 ? child.waitFor() >= 0
                    : child.waitFor(patienceMillis, TimeUnit.MILLISECONDS);
            if (!ended) {
                child.destroyForcibly().waitFor();
                return new Trial(false, 0, 0, 0, 0);
            }
            Matcher m = FIGURES.matcher(Files.readString(log));
            if (child.exitValue() != 0 || !m.find()) {
                return new Trial(false, 0, 0, 0, 0);
            }
            return new Trial(true, Integer.parseInt(m.group(1)), Integer.parseInt(m.group(2)),
                    Long.parseLong(m.group(3)), Long.parseLong(m.group(4)));
        } finally {
            Files.deleteIfExists(log);
        }
    }

    private static void child(Path file) throws Exception {
        long before = usedAfterGc();
        long start = System.nanoTime();
        Network network = ModelLoader.load(file);
        long millis = (System.nanoTime() - start) / 1_000_000;
        long retained = usedAfterGc() - before;
        System.out.printf("processes=%d edges=%d millis=%d retained=%d%n", network.processes().size(),
                network.processes().stream().mapToInt(p -> p.edges().size()).sum(), millis, retained);
        Reference.reachabilityFence(network);
    }

    private static long usedAfterGc() {
        for (int i = 0; i < 3; i++) {
            System.gc();
        }
        return ManagementFactory.getMemoryMXBean().getHeapMemoryUsage().getUsed();
    }
}
