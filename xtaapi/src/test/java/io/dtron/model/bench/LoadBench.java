package io.dtron.model.bench;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.util.Arrays;

/**
 * Load benchmark: a generated model with 1,000 processes and a generated 1 MB model, loaded (parsed,
 * resolved, type-checked, instantiated) from text. Prints the first load in this JVM (what a command-line
 * user waits for) and the median and maximum of later loads. Run with
 * {@code mvn -pl xtaapi -q test-compile exec:java -Dexec.classpathScope=test
 * -Dexec.mainClass=io.dtron.model.bench.LoadBench}. With {@code --write DIR} it writes the two models to
 * {@code DIR/many.xml} and {@code DIR/large.xml} instead, for {@code scripts/check-bench.sh}.
 */
public final class LoadBench {
    private static final int RUNS = 15;

    private LoadBench() {
    }

    public static void main(String[] args) throws Exception {
        if (args.length == 2 && args[0].equals("--write")) {
            java.nio.file.Path dir = java.nio.file.Path.of(args[1]);
            java.nio.file.Files.writeString(dir.resolve("many.xml"), GeneratedModels.manyProcesses(1000));
            java.nio.file.Files.writeString(dir.resolve("large.xml"), GeneratedModels.largeFile(1 << 20));
            return;
        }
        System.out.printf("machine: %d cores, Java %s, %s%n", Runtime.getRuntime().availableProcessors(),
                System.getProperty("java.version"), System.getProperty("os.name"));
        String many = GeneratedModels.manyProcesses(1000);
        String large = GeneratedModels.largeFile(1 << 20);
        measure("1,000 processes (" + many.length() / 1024 + " KiB)", "many.xml", many);
        measure("1 MB file (" + large.length() / 1024 + " KiB)", "large.xml", large);
    }

    private static void measure(String what, String name, String text) throws Exception {
        long start = System.nanoTime();
        Network first = ModelLoader.load(name, text);
        double cold = (System.nanoTime() - start) / 1e6;
        double[] times = new double[RUNS];
        for (int i = 0; i < RUNS; i++) {
            long t = System.nanoTime();
            ModelLoader.load(name, text);
            times[i] = (System.nanoTime() - t) / 1e6;
        }
        Arrays.sort(times);
        System.out.printf("%-28s processes=%d edges=%d  first load %.0f ms, then median %.0f ms, max %.0f ms (%d runs)%n",
                what, first.processes().size(), first.processes().stream().mapToInt(p -> p.edges().size()).sum(),
                cold, times[RUNS / 2], times[RUNS - 1], RUNS);
    }
}
