package io.dtron.cli;

import io.dtron.api.BusRecord;
import io.dtron.bridge.BusBridge;
import io.dtron.engine.JsonString;
import io.dtron.engine.Adapter;
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
import java.util.function.Consumer;

/**
 * Writes a run as JSON lines: a {@code start} line with the seed and settings, one line per input and output
 * with its time (an output with the window the model allowed it in, {@code allowed_from_us} to {@code
 * allowed_until_us}, -1 for the end of the test), a {@code due} line when the deadline of the next output changes
 * (the time by which the model requires an output while the tester waits for it, -1 when it waits for something
 * else), an {@code edges} line for each of them once the tester has committed to it (the edges it took for certain
 * and possibly), a {@code coverage}
 * line with what the run covered (the coverage file's object, on one line), and the {@code verdict} line. In
 * virtual time the same seed gives the same file, byte for byte. On
 * the bus, a {@code bus} line for every message on the bus while the run lasts, in the bus's order, with its sender's
 * stamps and its receive time: the global trace, the same order at every member.
 *
 * <p>A trace may be bounded ({@code --trace-max-size}): it stops there. The lines of events that would take it past
 * the bound are left out, and a {@code truncated} line (the bound, how many lines were left out, the time of the last
 * event written) comes before the {@code coverage} and {@code verdict} lines; the verdict always ends the trace: the
 * file holds the start of the run, its coverage and its verdict, at most the bound plus those three lines.
 */
final class JsonTrace implements TestListener {
    /** No bound. */
    static final long UNBOUNDED = Long.MAX_VALUE;

    private final Writer out;
    private final long unitMicros;
    private final Counted counted;
    private final long maxBytes;
    private long lastMicros = -1;
    private long omitted;
    private long omittedAfterMicros = -1;
    /** The deadline the last {@code due} line said; written on the tester's thread only. */
    private long due = -1;
    /** The window the model allowed the next output in, as the tester last said; on the tester's thread only. */
    private long windowFrom = -1;
    private long windowUntil = -1;

    private JsonTrace(Writer out, long unitMicros, Counted counted, long maxBytes) {
        this.out = out;
        this.unitMicros = unitMicros;
        this.counted = counted;
        this.maxBytes = maxBytes;
    }

    /** The bytes written to a stream. */
    private static final class Counted extends java.io.FilterOutputStream {
        private long bytes;

        Counted(java.io.OutputStream out) {
            super(out);
        }

        @Override
        public void write(int b) throws IOException {
            out.write(b);
            bytes++;
        }

        @Override
        public void write(byte[] b, int off, int len) throws IOException {
            out.write(b, off, len);
            bytes += len;
        }
    }

    /**
     * Runs the tester, writing the run to {@code file} when one is given.
     *
     * @throws IOException if the trace file cannot be written
     */
    static TestResult run(OnlineTester tester, Path file, Path model, TestOptions options) throws IOException {
        return run(tester, file, model, options, null, UNBOUNDED, note -> { });
    }

    /**
     * Runs the tester, writing the run to {@code file} when one is given, with every message on the bus when the
     * adapter is the bus bridge, and at most {@code maxBytes} of events ({@link #UNBOUNDED} for no bound); when the
     * bound cut the trace short, tells {@code note} so in a sentence after the run.
     *
     * @throws IOException if the trace file cannot be written
     */
    static TestResult run(OnlineTester tester, Path file, Path model, TestOptions options, Adapter adapter,
                          long maxBytes, Consumer<String> note) throws IOException {
        if (file == null) {
            return tester.run();
        }
        Counted counted = new Counted(Files.newOutputStream(file));
        try (Writer writer = new java.io.BufferedWriter(new java.io.OutputStreamWriter(counted,
                StandardCharsets.UTF_8))) {
            JsonTrace json = new JsonTrace(writer, options.timeUnitMicros(), counted, maxBytes);
            try {
                return run(tester, json, model, options, adapter);
            } finally {
                String truncated = json.truncation(file);
                if (truncated != null) {
                    note.accept(truncated);
                }
            }
        }
    }

    /** The sentence that says where the bound cut the trace {@code file} short, or null if it did not. */
    private synchronized String truncation(Path file) {
        return omitted == 0 ? null : "the trace " + file + " stopped at its bound of " + maxBytes + " bytes"
                + (omittedAfterMicros < 0 ? "" : " after the event at t_us " + omittedAfterMicros) + ": " + omitted
                + " later lines were left out; its last line is the verdict";
    }

    private static TestResult run(OnlineTester tester, JsonTrace json, Path model, TestOptions options,
                                  Adapter adapter) {
        json.start(options.seed(), model.toString(), options.timeout(), options.virtualTime());
        tester.addListener(json);
        if (!(adapter instanceof BusBridge bridge)) {
            return tester.run();
        }
        Consumer<BusRecord> bus = json::bus;
        bridge.run().addRecordListener(bus);
        try {
            return tester.run();
        } finally {
            bridge.run().removeRecordListener(bus);
        }
    }

    /** A message on the bus. */
    void bus(BusRecord r) {
        bounded(-1, "{\"kind\":\"bus\",\"channel\":" + quote(r.channel()) + ",\"sender\":" + quote(r.sender())
                + ",\"sequence\":" + r.sequence() + ",\"run\":" + quote(r.runId()) + ",\"publish_ns\":"
                + r.publishTimeNanos() + ",\"event_ns\":" + r.eventTimeNanos() + ",\"receive_ns\":"
                + r.receiveTimeNanos() + ",\"offset_ns\":" + r.clockOffsetNanos() + ",\"error_ns\":"
                + r.clockErrorNanos() + (r.ackedSender().isEmpty() ? "" : ",\"acked_sender\":" + quote(r.ackedSender())
                + ",\"acked_sequence\":" + r.ackedSequence()) + ",\"values\":" + values(r.variables()) + "}");
    }

    void start(long seed, String model, long timeout, boolean virtualTime) {
        line("{\"kind\":\"start\",\"seed\":" + seed + ",\"model\":" + quote(model) + ",\"timeunit_us\":" + unitMicros
                + ",\"timeout\":" + timeout + ",\"virtual_time\":" + virtualTime + "}");
    }

    @Override
    public void inputApplied(Event input, long micros) {
        event("input", input, micros, "");
    }

    @Override
    public void outputWindow(Event output, long micros, long earliestMicros, long latestMicros) {
        windowFrom = earliestMicros;
        windowUntil = latestMicros;
    }

    @Override
    public void outputObserved(Event output, long micros) {
        String window = windowFrom < 0 ? "" : ",\"allowed_from_us\":" + windowFrom + ",\"allowed_until_us\":"
                + windowUntil;
        windowFrom = -1;
        windowUntil = -1;
        event("output", output, micros, window);
    }

    @Override
    public void waiting(long nowMicros, long untilMicros, Until until) {
        long deadline = until == Until.OUTPUT_DEADLINE ? untilMicros : -1;
        if (deadline != due) {
            due = deadline;
            bounded(nowMicros, "{\"kind\":\"due\",\"t_us\":" + nowMicros + ",\"until_us\":" + deadline + "}");
        }
    }

    @Override
    public void edgesTaken(Event event, boolean input, long micros, java.util.List<String> certainly,
                           java.util.List<String> possibly) {
        bounded(micros, "{\"kind\":\"edges\",\"t_us\":" + micros + ",\"channel\":" + quote(event.channel())
                + ",\"input\":" + input + ",\"certainly\":" + strings(certainly) + ",\"possibly\":"
                + strings(possibly) + "}");
    }

    private static String strings(java.util.List<String> list) {
        StringBuilder sb = new StringBuilder("[");
        for (String s : list) {
            sb.append(sb.length() == 1 ? "" : ",").append(quote(s));
        }
        return sb.append(']').toString();
    }

    @Override
    public void finished(TestResult r) {
        synchronized (this) {
            if (omitted > 0) {
                line("{\"kind\":\"truncated\",\"max_bytes\":" + maxBytes + ",\"omitted_lines\":" + omitted
                        + ",\"after_t_us\":" + omittedAfterMicros + "}");
            }
        }
        if (r.coverage() != null) {
            // the coverage file's text has line breaks only between its tokens: strings escape theirs
            line("{\"kind\":\"coverage\",\"coverage\":" + CoverageJson.write(r.coverage()).replace("\n", "")
                    + "}");
        }
        line("{\"kind\":\"verdict\",\"t_us\":" + r.durationMicros() + ",\"verdict\":\"" + r.verdict()
                + "\",\"seed\":" + r.seed() + ",\"inputs\":" + r.inputs() + ",\"outputs\":" + r.outputs()
                + ",\"explanation\":" + quote(r.explanation()) + "}");
    }

    private void event(String kind, Event e, long micros, String more) {
        bounded(micros, "{\"kind\":\"" + kind + "\",\"t_us\":" + micros + ",\"channel\":" + quote(e.channel())
                + ",\"values\":" + values(e.values()) + more + "}");
    }

    private static String values(Map<String, Integer> variables) {
        StringBuilder values = new StringBuilder("{");
        for (Map.Entry<String, Integer> v : variables.entrySet()) {
            values.append(values.length() == 1 ? "" : ",").append(quote(v.getKey())).append(':').append(v.getValue());
        }
        return values.append('}').toString();
    }

    /**
     * Writes the line of an event at {@code micros} (-1 for a message on the bus) unless the trace reached its bound:
     * then it is counted as left out.
     */
    private synchronized void bounded(long micros, String json) {
        if (omitted == 0 && counted.bytes + json.length() + 1 <= maxBytes) {
            line(json);
            lastMicros = micros >= 0 ? micros : lastMicros;
            return;
        }
        if (omitted++ == 0) {
            omittedAfterMicros = lastMicros;
        }
    }

    /** Writes one line; the engine's thread and the bus's write lines. */
    private synchronized void line(String json) {
        try {
            out.write(json);
            out.write('\n');
            out.flush();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** A JSON string literal (see {@link JsonString}). */
    static String quote(String s) {
        return JsonString.quote(s);
    }
}
