package io.dtron.cli;

import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.io.Writer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Map;

/**
 * Writes a run as JSON lines: a {@code start} line with the seed and settings, one line per input and output
 * with its time, and a {@code verdict} line. In virtual time the same seed gives the same file, byte for byte.
 */
final class JsonTrace implements TestListener {
    private final Writer out;
    private final long unitMicros;

    JsonTrace(Writer out, long unitMicros) {
        this.out = out;
        this.unitMicros = unitMicros;
    }

    /**
     * Runs the tester, writing the run to {@code file} when one is given.
     *
     * @throws IOException if the trace file cannot be written
     */
    static TestResult run(OnlineTester tester, Path file, Path model, TestOptions options) throws IOException {
        if (file == null) {
            return tester.run();
        }
        try (Writer writer = Files.newBufferedWriter(file, StandardCharsets.UTF_8)) {
            JsonTrace json = new JsonTrace(writer, options.timeUnitMicros());
            json.start(options.seed(), model.toString(), options.timeout(), options.virtualTime());
            tester.addListener(json);
            return tester.run();
        }
    }

    void start(long seed, String model, long timeout, boolean virtualTime) {
        line("{\"kind\":\"start\",\"seed\":" + seed + ",\"model\":" + quote(model) + ",\"timeunit_us\":" + unitMicros
                + ",\"timeout\":" + timeout + ",\"virtual_time\":" + virtualTime + "}");
    }

    @Override
    public void inputApplied(Event input, long micros) {
        event("input", input, micros);
    }

    @Override
    public void outputObserved(Event output, long micros) {
        event("output", output, micros);
    }

    @Override
    public void finished(TestResult r) {
        line("{\"kind\":\"verdict\",\"t_us\":" + r.durationMicros() + ",\"verdict\":\"" + r.verdict() + "\",\"seed\":"
                + r.seed() + ",\"inputs\":" + r.inputs() + ",\"outputs\":" + r.outputs() + ",\"explanation\":"
                + quote(r.explanation()) + "}");
    }

    private void event(String kind, Event e, long micros) {
        StringBuilder values = new StringBuilder("{");
        for (Map.Entry<String, Integer> v : e.values().entrySet()) {
            values.append(values.length() == 1 ? "" : ",").append(quote(v.getKey())).append(':').append(v.getValue());
        }
        line("{\"kind\":\"" + kind + "\",\"t_us\":" + micros + ",\"channel\":" + quote(e.channel()) + ",\"values\":"
                + values.append('}') + "}");
    }

    private void line(String json) {
        try {
            out.write(json);
            out.write('\n');
            out.flush();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** A JSON string literal. */
    static String quote(String s) {
        StringBuilder sb = new StringBuilder("\"");
        for (int i = 0; i < s.length(); i++) {
            char c = s.charAt(i);
            switch (c) {
                case '"' -> sb.append("\\\"");
                case '\\' -> sb.append("\\\\");
                case '\n' -> sb.append("\\n");
                case '\r' -> sb.append("\\r");
                case '\t' -> sb.append("\\t");
                default -> {
                    if (c < 0x20) {
                        sb.append(String.format("\\u%04x", (int) c));
                    } else {
                        sb.append(c);
                    }
                }
            }
        }
        return sb.append('"').toString();
    }
}
