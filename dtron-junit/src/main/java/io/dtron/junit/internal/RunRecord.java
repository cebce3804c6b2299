package io.dtron.junit.internal;

import io.dtron.engine.Event;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestResult;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Locale;

/**
 * The text report of one run, written when it ends: what was tested, every input and output with its time in model
 * time units, the verdict with its explanation, the statistics and the coverage.
 */
final class RunRecord implements TestListener {
    private final StringBuilder text = new StringBuilder();
    private final long unitMicros;

    RunRecord(String header, long unitMicros) {
        this.unitMicros = unitMicros;
        text.append(header).append('\n');
    }

    @Override
    public synchronized void inputApplied(Event input, long micros) {
        line(micros, "input", input);
    }

    @Override
    public synchronized void outputObserved(Event output, long micros) {
        line(micros, "output", output);
    }

    private void line(long micros, String kind, Event event) {
        text.append(String.format(Locale.ROOT, "t=%.3f %s %s%n", micros / (double) unitMicros, kind, event));
    }

    /** Writes the report with the run's result to {@code file}. */
    synchronized void write(TestResult result, Path file) {
        text.append(result.verdict()).append(": ").append(result.explanation()).append('\n');
        text.append("statistics: ").append(result.statisticsLine())
                .append(" (seed verdict inputs outputs duration-us)\n");
        if (result.coverage() != null) {
            text.append(result.coverage().summary()).append('\n');
        }
        try {
            Files.createDirectories(file.toAbsolutePath().getParent());
            Files.writeString(file, text, StandardCharsets.UTF_8);
        } catch (IOException e) {
            throw new UncheckedIOException("cannot write the run's report " + file + ": " + e.getMessage(), e);
        }
    }
}
