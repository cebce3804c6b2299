package io.dtron.engine.verify;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

/**
 * The checker on the shared benchmark models (Fischer, CSMA/CD, FDDI), for the figures of
 * {@code src/site/markdown/benchmarks.md}: for each model given (file names under {@code
 * ../shared/models/benchmarks}, default: the set in benchmarks.md), wall time, explored and stored states and
 * the heap seen in use, for the model's first query (Fischer's mutual exclusion; {@code -DallQueries=true} for
 * all of them) or, for models without queries, the whole state space ({@code A[] true}). Each model runs {@code -Druns=N} times (default 2) in this JVM, after one warm-up
 * run of fischer-6. Run it with the test classpath; see benchmarks.md.
 */
public final class VerifyBench {
    private VerifyBench() {
    }

    public static void main(String[] args) throws Exception {
        Path dir = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "benchmarks");
        List<String> models = args.length > 0 ? List.of(args) : List.of("fischer-6.xml", "fischer-7.xml",
                "fischer-8.xml", "fischer-9.xml", "csmacd-6.xml", "csmacd-8.xml", "csmacd-9.xml", "csmacd-10.xml",
                "fddi-8.xml", "fddi-10.xml", "fddi-12.xml");
        int runs = Integer.getInteger("runs", 2);
        String order = System.getProperty("order", "bfs");
        VerifierOptions options = VerifierOptions.defaults().withOrder(order.equals("dfs") ? SearchOrder.DEPTH_FIRST
                : SearchOrder.BREADTH_FIRST);
        run(dir.resolve("fischer-6.xml"), options, 1, true);
        System.out.printf("%-14s %-16s %-10s %10s %10s %9s %8s%n", "model", "query", "answer", "explored", "stored",
                "seconds", "heap MB");
        for (String m : models) {
            run(dir.resolve(m), options, runs, false);
        }
    }

    private static void run(Path file, VerifierOptions options, int runs, boolean quiet) throws Exception {
        if (!Files.exists(file)) {
            throw new IllegalArgumentException("no model " + file);
        }
        for (int r = 0; r < runs; r++) {
            System.gc();
            Network network = ModelLoader.load(file);
            Verifier verifier = new Verifier(network, options);
            List<Query> queries = new ArrayList<>(verifier.modelQueries());
            if (queries.isEmpty()) {
                queries.add(Query.parse("A[] true"));
            } else if (!Boolean.getBoolean("allQueries")) {
                queries = queries.subList(0, 1);
            }
            for (Query q : queries) {
                VerificationResult result = verifier.verify(q);
                VerificationResult.Statistics s = result.statistics();
                if (!quiet) {
                    String text = q.text().length() > 16 ? q.text().substring(0, 13) + "..." : q.text();
                    System.out.printf("%-14s %-16s %-10s %,10d %,10d %9.2f %8d%n", file.getFileName(), text,
                            result.outcome(),
                            s.explored(), s.stored(), s.time().toNanos() / 1e9, s.memoryBytes() >> 20);
                }
            }
        }
    }
}
