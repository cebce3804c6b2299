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
import java.nio.ByteBuffer;
import java.nio.channels.Channels;
import java.nio.channels.FileChannel;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.util.Map;
import java.util.function.Consumer;

/**
 * Writes a run as JSON lines: a {@code start} line with the seed and settings, one line per input and output with its
 * time (an output with the window the model allowed it in, {@code allowed_from_us} to {@code allowed_until_us}, -1 for
 * the end of the test; an input at the time the tester placed it, which is when its adapter reported it applied, with
 * {@code sent_us} when that was later than the tester sent it), a {@code due} line when the deadline of the next output
 * changes (the time by which the model requires an output while the tester waits for it, -1 when it waits for something
 * else), an {@code edges} line for each of them once the tester has committed to it (the edges it took for certain and
 * possibly), a {@code coverage} line with what the run covered (the coverage file's object, on one line), and the
 * {@code verdict} line. In virtual time the same seed gives the same file, byte for byte. On the bus, a {@code bus}
 * line for every message on the bus while the run lasts, in the bus's order, with its sender's stamps and its receive
 * time: the global trace, the same order at every member.
 *
 * <p>A trace may be bounded ({@code --trace-max-size}): the whole file stays within the bound. The lines of events
 * that would take it past the bound are left out, and at the end the last events written give way to the lines that
 * end every trace: a {@code truncated} line (the bound, how many lines were left out, the time of the last event
 * kept), the {@code coverage} and the {@code verdict} lines. Only a bound too small for the start line and those
 * alone is passed, by them.
 */
final class JsonTrace implements TestListener {
    /** No bound. */
    static final long UNBOUNDED = Long.MAX_VALUE;

    /** The most bytes a {@code truncated} line takes, with its newline. */
    private static final int TRUNCATED_ROOM = truncatedLine(Long.MAX_VALUE, Long.MAX_VALUE, Long.MIN_VALUE).length()
            + 1;

    private final Writer out;
    private final long unitMicros;
    private final Counted counted;
    /** The file, to give the last events' room to the lines that end the trace; null when it is not bounded. */
    private final FileChannel file;
    private final long maxBytes;
    /** Where the start line ends: the events begin there. */
    private long startEnd;
    private long lastMicros = -1;
    private long omitted;
    private long omittedAfterMicros = -1;
    /** The deadline the last {@code due} line said; written on the tester's thread only. */
    private long due = -1;
    /** The window the model allowed the next output in, as the tester last said; on the tester's thread only. */
    private long windowFrom = -1;
    private long windowUntil = -1;
    /**
     * The tester's lines held behind an input whose time is not known yet (its adapter reports when it applied it):
     * an input's line carries the time the tester placed it at, and the lines stay in the order of their times.
     * On the tester's thread only.
     */
    private final java.util.List<Held> held = new java.util.ArrayList<>();

    private JsonTrace(Writer out, long unitMicros, Counted counted, FileChannel file, long maxBytes) {
        this.out = out;
        this.unitMicros = unitMicros;
        this.counted = counted;
        this.file = file;
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
        FileChannel channel = FileChannel.open(file, StandardOpenOption.CREATE, StandardOpenOption.TRUNCATE_EXISTING,
                StandardOpenOption.WRITE, StandardOpenOption.READ);
        Counted counted = new Counted(Channels.newOutputStream(channel));
        try (Writer writer = new java.io.BufferedWriter(new java.io.OutputStreamWriter(counted,
                StandardCharsets.UTF_8))) {
            JsonTrace json = new JsonTrace(writer, options.timeUnitMicros(), counted,
                    maxBytes == UNBOUNDED ? null : channel, maxBytes);
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
        startEnd = counted.bytes;
    }

    @Override
    public void inputApplied(Event input, long micros) {
        held.add(new Held(micros, input, null));
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
        later(micros, eventLine("output", output, micros, window));
    }

    @Override
    public void waiting(long nowMicros, long untilMicros, Until until) {
        long deadline = until == Until.OUTPUT_DEADLINE ? untilMicros : -1;
        if (deadline != due) {
            due = deadline;
            later(nowMicros, "{\"kind\":\"due\",\"t_us\":" + nowMicros + ",\"until_us\":" + deadline + "}");
        }
    }

    @Override
    public void edgesTaken(Event event, boolean input, long micros, java.util.List<String> certainly,
                           java.util.List<String> possibly) {
        if (input) {
            place(event, micros);
        }
        later(micros, "{\"kind\":\"edges\",\"t_us\":" + micros + ",\"channel\":" + quote(event.channel())
                + ",\"input\":" + input + ",\"certainly\":" + strings(certainly) + ",\"possibly\":"
                + strings(possibly) + "}");
        flush(false);
    }

    /**
     * A line of the tester's, held while an input before it waits for its time: an input's line (its event, with
     * {@code line} null) until the tester commits to where it was applied, or any other line behind it.
     */
    private static final class Held {
        long micros;
        final Event input;
        final String line;
        /** When the tester sent the input, for an input's line. */
        final long sentMicros;
        boolean placed;

        Held(long micros, Event input, String line) {
            this.micros = micros;
            this.input = input;
            this.line = line;
            this.sentMicros = micros;
            this.placed = input == null;
        }
    }

    /**
     * Places the first input on {@code event}'s channel still waiting for its time at {@code micros}, where the
     * tester committed to it: an adapter that reports when it applied an input (later than it was sent) moves it.
     */
    private void place(Event event, long micros) {
        for (Held h : held) {
            if (!h.placed && h.input.channel().equals(event.channel())) {
                h.micros = micros;
                h.placed = true;
                return;
            }
        }
    }

    /** Writes {@code json}, of a line at {@code micros}, now, or after the inputs held before it. */
    private void later(long micros, String json) {
        if (held.isEmpty()) {
            bounded(micros, json);
        } else {
            held.add(new Held(micros, null, json));
        }
    }

    /**
     * Writes the held lines in the order of their times (stable: lines of one time stay in the order they came) up
     * to the first input still waiting for its time, or all of them when {@code all} (the run ended: an input
     * never committed to keeps the time it was sent at).
     */
    private void flush(boolean all) {
        held.sort(java.util.Comparator.comparingLong(h -> h.micros));
        while (!held.isEmpty() && (all || held.get(0).placed)) {
            Held h = held.remove(0);
            if (h.input != null) {
                bounded(h.micros, eventLine("input", h.input, h.micros, h.micros == h.sentMicros ? ""
                        : ",\"sent_us\":" + h.sentMicros));
            } else {
                bounded(h.micros, h.line);
            }
        }
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
        flush(true);
        // the coverage file's text has line breaks only between its tokens: strings escape theirs
        String coverage = r.coverage() == null ? null : "{\"kind\":\"coverage\",\"coverage\":"
                + CoverageJson.write(r.coverage()).replace("\n", "") + "}";
        String verdict = "{\"kind\":\"verdict\",\"t_us\":" + r.durationMicros() + ",\"verdict\":\"" + r.verdict()
                + "\",\"seed\":" + r.seed() + ",\"inputs\":" + r.inputs() + ",\"outputs\":" + r.outputs()
                + ",\"explanation\":" + quote(r.explanation()) + "}";
        synchronized (this) {
            long end = maxBytes - bytes(verdict) - (coverage == null ? 0 : bytes(coverage));
            if (file != null && (omitted > 0 || counted.bytes > end)) {
                makeRoom(end - TRUNCATED_ROOM);
            }
            if (omitted > 0) {
                line(truncatedLine(maxBytes, omitted, omittedAfterMicros));
            }
        }
        if (coverage != null) {
            line(coverage);
        }
        line(verdict);
    }

    private static String truncatedLine(long maxBytes, long omitted, long afterMicros) {
        return "{\"kind\":\"truncated\",\"max_bytes\":" + maxBytes + ",\"omitted_lines\":" + omitted
                + ",\"after_t_us\":" + afterMicros + "}";
    }

    /** The bytes of {@code line} in the file, with its newline. */
    private static long bytes(String line) {
        return line.getBytes(StandardCharsets.UTF_8).length + 1L;
    }

    /**
     * Cuts the last lines of events off the file until it ends at or before {@code limit} (never into the start
     * line), counting them as left out, and the time of the last event kept as the one after which lines were.
     */
    private void makeRoom(long limit) {
        try {
            long cut = counted.bytes;
            long cutLines = 0;
            BackwardLines lines = new BackwardLines(file, startEnd, counted.bytes);
            while (cut > limit && lines.hasPrevious()) {
                cut -= lines.previous().length + 1;
                cutLines++;
            }
            if (cutLines == 0) {
                return;
            }
            long after = -1;
            while (after < 0 && lines.hasPrevious()) {
                after = micros(new String(lines.previous(), StandardCharsets.UTF_8));
            }
            file.truncate(cut);
            counted.bytes = cut;
            omitted += cutLines;
            omittedAfterMicros = after;
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** The {@code t_us} of an event's line, or -1 when it has none (a message on the bus). */
    private static long micros(String line) {
        int at = line.indexOf("\"t_us\":");
        if (at < 0) {
            return -1;
        }
        int from = at + "\"t_us\":".length();
        int to = from;
        while (to < line.length() && (Character.isDigit(line.charAt(to)) || line.charAt(to) == '-')) {
            to++;
        }
        return Long.parseLong(line, from, to, 10);
    }

    /** The lines of a part of a file, read from its end backward, a block at a time. */
    private static final class BackwardLines {
        private static final int BLOCK = 1 << 16;
        private final FileChannel file;
        private final long from;
        /** Where the next line read ends (its newline is the byte there). */
        private long end;

        /** The lines of {@code file} between {@code from} and {@code end}, each ending with a newline. */
        BackwardLines(FileChannel file, long from, long end) {
            this.file = file;
            this.from = from;
            this.end = end - 1;
        }

        boolean hasPrevious() {
            return end > from;
        }

        /** The line before the last one read, without its newline. */
        byte[] previous() throws IOException {
            java.io.ByteArrayOutputStream reversed = new java.io.ByteArrayOutputStream();
            long pos = end;
            ByteBuffer block = ByteBuffer.allocate(BLOCK);
            while (pos > from) {
                int size = (int) Math.min(BLOCK, pos - from);
                block.clear().limit(size);
                long at = pos - size;
                while (block.hasRemaining() && file.read(block, at + block.position()) >= 0) {
                    // reads the whole block
                }
                for (int i = size - 1; i >= 0; i--) {
                    if (block.get(i) == '\n') {
                        end = at + i;
                        return reverse(reversed.toByteArray());
                    }
                    reversed.write(block.get(i));
                }
                pos = at;
            }
            end = from;
            return reverse(reversed.toByteArray());
        }

        private static byte[] reverse(byte[] b) {
            for (int i = 0, j = b.length - 1; i < j; i++, j--) {
                byte t = b[i];
                b[i] = b[j];
                b[j] = t;
            }
            return b;
        }
    }

    private static String eventLine(String kind, Event e, long micros, String more) {
        return "{\"kind\":\"" + kind + "\",\"t_us\":" + micros + ",\"channel\":" + quote(e.channel())
                + ",\"values\":" + values(e.values()) + more + "}";
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
