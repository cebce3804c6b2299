package io.dtron.models.lamp;

import io.dtron.cli.DtronCommand;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.io.Writer;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Locale;

/**
 * How long {@code dtron report} takes for a trace of at least 100,000 inputs and outputs: the shared LightContr run
 * in virtual time against the bundled lamp long enough, once, with {@code --trace}; then the report made from that
 * trace in this JVM, round after round (wall time and the thread's CPU time, which a busy machine disturbs less).
 *
 * <p>{@code java -cp ... io.dtron.models.lamp.ReportBench [SHARED_MODELS] [ROUNDS]}
 */
public final class ReportBench {
    private ReportBench() {
    }

    public static void main(String[] args) throws Exception {
        Path shared = Path.of(args.length > 0 ? args[0] : "../shared/models");
        int rounds = args.length > 1 ? Integer.parseInt(args[1]) : 10;
        Path dir = Files.createTempDirectory("report-bench");
        Files.copy(shared.resolve("tron/LightContr.xml"), dir.resolve("LightContr.xml"));
        Files.copy(shared.resolve("tron/LightContr.trn"), dir.resolve("LightContr.trn"));
        Path trace = dir.resolve("run.jsonl");
        Path page = dir.resolve("run.html");
        Writer quiet = new StringWriter();
        int exit = DtronCommand.run(new String[] {"run", dir.resolve("LightContr.xml").toString(), "--interface",
                dir.resolve("LightContr.trn").toString(), "--sut", SmartLamp.class.getName(), "--virtual-time",
                "--seed", "1", "--timeout", "10000000", "--trace", trace.toString()}, new PrintWriter(quiet),
                new PrintWriter(quiet));
        long events;
        try (var lines = Files.lines(trace)) {
            events = lines.filter(l -> l.startsWith("{\"kind\":\"input\"") || l.startsWith("{\"kind\":\"output\""))
                    .count();
        }
        System.out.printf(Locale.ROOT, "trace: %d inputs and outputs, %d lines, %.1f MB (run exit %d)%n", events,
                Files.lines(trace).count(), Files.size(trace) / 1e6, exit);
        java.lang.management.ThreadMXBean threads = java.lang.management.ManagementFactory.getThreadMXBean();
        for (int r = 0; r < rounds; r++) {
            long start = System.nanoTime();
            long cpu = threads.getCurrentThreadCpuTime();
            StringWriter out = new StringWriter();
            int code = DtronCommand.run(new String[] {"report", trace.toString(), "-o", page.toString()},
                    new PrintWriter(out), new PrintWriter(out));
            double seconds = (System.nanoTime() - start) / 1e9;
            double cpuSeconds = (threads.getCurrentThreadCpuTime() - cpu) / 1e9;
            System.out.printf(Locale.ROOT, "round %d: report in %.2f s (%.2f s of CPU), page %.1f MB, exit %d%n",
                    r + 1, seconds, cpuSeconds, Files.size(page) / 1e6, code);
        }
        System.out.println("page: " + page);
    }
}
