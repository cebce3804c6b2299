package io.dtron.cli;

import io.dtron.engine.Event;
import io.dtron.engine.TestOptions;
import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.nio.charset.CharsetDecoder;
import java.nio.charset.CodingErrorAction;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;

/**
 * Reads the events of a recorded run for {@code dtron monitor --replay}, line by line: JSON lines (DTRON's own
 * traces, {@code dtron run --trace}, and logs of the same shape) or CSV ({@code t_us,channel,values}). A line that
 * cannot be read is handed on as rejected, with the reason, and the reading goes on.
 *
 * <p>JSON lines: an object with {@code "t_us"} (microseconds on the run's clock), {@code "channel"} and optionally
 * {@code "values"} (an object of integers) is an event when its {@code "kind"} is {@code "input"}, {@code "output"}
 * or absent; {@code "verdict"} ends the observation at its {@code t_us}, or at the {@code start} line's timeout
 * when that comes first, or at the last event a {@code truncated} line (a trace bounded by {@code --trace-max-size})
 * names; {@code start}, {@code edges}, {@code due}, {@code coverage}, {@code bus} and {@code alarm} lines are skipped.
 * CSV: one event a line, {@code t_us,channel,values} with
 * the values as {@code name=value} pairs separated by {@code ;} (empty for none), any field in double quotes as RFC
 * 4180 has it ({@link #fields}); a first line starting with {@code t_us} is a header; blank lines and lines starting
 * with {@code #} are skipped.
 */
final class TraceReader {
    /** The formats. */
    enum Format { JSON_LINES, CSV }

    /** Receives what the lines say. */
    interface Sink {
        /** An event at {@code micros}, on line {@code line}. */
        void event(Event event, long micros, int line);

        /** The end of the run at {@code micros} (a verdict line). */
        void end(long micros, int line);

        /** Line {@code line} could not be read, for {@code reason}. */
        void rejected(int line, String reason);
    }

    private TraceReader() {
    }

    /** The format of {@code file}: CSV when its name ends with {@code .csv}, else JSON lines. */
    static Format formatOf(Path file) {
        return file.getFileName().toString().toLowerCase(Locale.ROOT).endsWith(".csv") ? Format.CSV : Format.JSON_LINES;
    }

    /**
     * The time unit a DTRON trace names on its {@code start} line ({@code timeunit_us}), or null.
     *
     * @throws IOException if the file cannot be read
     */
    static Long timeUnit(Path file) throws IOException {
        try (BufferedReader in = reader(file)) {
            String first = withoutByteOrderMark(in.readLine());
            if (first == null || !first.strip().startsWith("{")) {
                return null;
            }
            Map<?, ?> m;
            try {
                m = Json.parse(first.strip()) instanceof Map<?, ?> parsed ? parsed : Map.of();
            } catch (IllegalArgumentException e) {
                return null; // the reading rejects the line, saying why
            }
            Object unit = m.get("timeunit_us");
            if (!"start".equals(m.get("kind")) || unit == null) {
                return null;
            }
            if (unit instanceof Long micros && micros > 0 && micros <= TestOptions.MAX_DURATION_MICROS) {
                return micros;
            }
            throw new IllegalArgumentException("the start line's timeunit_us " + Json.text(unit) + " is no"
                    + " positive number of microseconds (at most " + TestOptions.MAX_DURATION_MICROS + ")");
        }
    }

    /**
     * A reader of {@code file} as UTF-8 that does not stop at bytes that are not UTF-8: they become U+FFFD, and the
     * line holding them is rejected.
     */
    private static BufferedReader reader(Path file) throws IOException {
        CharsetDecoder utf8 = StandardCharsets.UTF_8.newDecoder().onMalformedInput(CodingErrorAction.REPLACE)
                .onUnmappableCharacter(CodingErrorAction.REPLACE);
        return new BufferedReader(new InputStreamReader(Files.newInputStream(file), utf8));
    }

    /** {@code line} without the byte order mark some editors put at the start of a UTF-8 file. */
    private static String withoutByteOrderMark(String line) {
        return line != null && line.startsWith("\uFEFF") ? line.substring(1) : line;
    }

    /**
     * Reads {@code file} in {@code format}, handing each line's meaning to {@code sink}.
     *
     * @throws IOException if the file cannot be read
     */
    static void read(Path file, Format format, Sink sink) throws IOException {
        try (BufferedReader in = reader(file)) {
            String line;
            int number = 0;
            boolean first = true;
            long[] timeout = {Long.MAX_VALUE};
            while ((line = in.readLine()) != null) {
                number++;
                String trimmed = (number == 1 ? withoutByteOrderMark(line) : line).strip();
                if (trimmed.isEmpty()) {
                    continue;
                }
                if (trimmed.indexOf('\uFFFD') >= 0) {
                    sink.rejected(number, "not UTF-8 text (a byte at column " + (line.indexOf('\uFFFD') + 1)
                            + " is no UTF-8 character)");
                    first = false;
                    continue;
                }
                try {
                    if (format == Format.CSV) {
                        if (trimmed.startsWith("#") || first && (trimmed.startsWith("t_us")
                                || trimmed.startsWith("\"t_us\""))) {
                            first = false;
                            continue;
                        }
                        first = false;
                        csv(trimmed, number, sink);
                    } else {
                        json(trimmed, number, sink, timeout);
                    }
                } catch (IllegalArgumentException e) {
                    // the line is the file's: a JSON error's "line 1" inside it would contradict the file's line
                    sink.rejected(number, e.getMessage().replaceFirst("^line 1, column ", "column "));
                }
            }
        }
    }

    /**
     * One JSON line; {@code timeout} holds the end of the test a {@code start} line set (its timeout in time units
     * times its time unit), for the {@code verdict} line after it.
     */
    private static void json(String line, int number, Sink sink, long[] timeout) {
        Map<?, ?> m = Flat.parse(line);
        if (m == null) {
            if (!(Json.parse(line) instanceof Map<?, ?> parsed)) {
                throw new IllegalArgumentException("not a JSON object");
            }
            m = parsed;
        }
        Object kind = m.get("kind");
        if ("start".equals(kind) && m.get("timeout") instanceof Long units && m.get("timeunit_us") instanceof Long unit
                && units > 0 && unit > 0 && units <= Long.MAX_VALUE / unit) {
            timeout[0] = units * unit;
            return;
        }
        if ("truncated".equals(kind)) {
            // a bounded trace (--trace-max-size) left out the events after this time: the observation ends there,
            // or a deadline those events met would look missed
            timeout[0] = Math.min(timeout[0], m.get("after_t_us") instanceof Long after ? Math.max(0, after) : 0);
            return;
        }
        if ("verdict".equals(kind)) {
            // the tester observes until its timeout; its verdict's time may be later, when the run wound up
            sink.end(Math.min(micros(m.get("t_us")), timeout[0]), number);
            return;
        }
        if (kind != null && !"input".equals(kind) && !"output".equals(kind)) {
            if ("start".equals(kind) || "edges".equals(kind) || "bus".equals(kind) || "alarm".equals(kind)
                    || "due".equals(kind) || "coverage".equals(kind)) {
                return;
            }
            throw new IllegalArgumentException("unknown kind " + kind + " (an event is of kind input or output, or"
                    + " has none)");
        }
        if (!(m.get("channel") instanceof String channel) || channel.isEmpty()) {
            throw new IllegalArgumentException("no \"channel\" string");
        }
        Map<String, Integer> values = new LinkedHashMap<>();
        Object v = m.get("values");
        if (v != null) {
            if (!(v instanceof Map<?, ?> vm)) {
                throw new IllegalArgumentException("\"values\" is not an object");
            }
            for (Map.Entry<?, ?> e : vm.entrySet()) {
                values.put((String) e.getKey(), integer(e.getKey() + "", e.getValue()));
            }
        }
        sink.event(new Event(channel, values), micros(m.get("t_us")), number);
    }

    private static long micros(Object t) {
        if (!(t instanceof Long micros)) {
            throw new IllegalArgumentException("no \"t_us\" integer (the time in microseconds)");
        }
        return checked(micros);
    }

    /** {@code micros}, a time of the run, if DTRON can time it. */
    private static long checked(long micros) {
        if (micros < 0) {
            throw new IllegalArgumentException("negative time " + micros);
        }
        if (micros > TestOptions.MAX_DURATION_MICROS) {
            throw new IllegalArgumentException("time " + micros + " us is later than DTRON can time (at most "
                    + TestOptions.MAX_DURATION_MICROS + " us, about 292 years)");
        }
        return micros;
    }

    private static int integer(String name, Object value) {
        if (!(value instanceof Long l) || l < Integer.MIN_VALUE || l > Integer.MAX_VALUE) {
            throw new IllegalArgumentException("value of '" + name + "' is not a 32-bit integer: " + Json.text(value));
        }
        return (int) (long) l;
    }

    private static void csv(String line, int number, Sink sink) {
        List<String> split = fields(line);
        if (split.size() < 2 || split.size() > 3) {
            throw new IllegalArgumentException("expected t_us,channel,values: " + split.size() + " fields");
        }
        String[] fields = split.toArray(String[]::new);
        long micros;
        try {
            micros = Long.parseLong(fields[0].strip());
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException("time '" + fields[0].strip() + "' is no whole number of microseconds");
        }
        checked(micros);
        String channel = fields[1].strip();
        if (channel.isEmpty()) {
            throw new IllegalArgumentException("no channel");
        }
        Map<String, Integer> values = new LinkedHashMap<>();
        String given = fields.length == 3 ? fields[2].strip() : "";
        if (!given.isEmpty()) {
            for (String pair : given.split(";", -1)) {
                int eq = pair.indexOf('=');
                String name = eq < 0 ? "" : pair.substring(0, eq).strip();
                if (name.isEmpty()) {
                    throw new IllegalArgumentException("value '" + pair.strip() + "' is not name=value");
                }
                try {
                    if (values.put(name, Integer.parseInt(pair.substring(eq + 1).strip())) != null) {
                        throw new IllegalArgumentException("'" + name + "' given twice");
                    }
                } catch (NumberFormatException e) {
                    throw new IllegalArgumentException("value of '" + name + "' is not a 32-bit integer: "
                            + pair.substring(eq + 1).strip());
                }
            }
        }
        sink.event(new Event(channel, values), micros, number);
    }

    /**
     * The fields of a CSV line, quoted as RFC 4180 quotes them: a field in double quotes may hold commas, and a
     * double quote doubled ({@code ""}) stands for one; a field cannot span lines.
     *
     * @throws IllegalArgumentException if a quote is not closed, or a quoted field is followed by more than a comma
     */
    static List<String> fields(String line) {
        List<String> fields = new ArrayList<>();
        int at = 0;
        while (true) {
            int start = at;
            while (at < line.length() && line.charAt(at) == ' ') {
                at++; // spaces before a quote, as after a comma in "1000, req"
            }
            StringBuilder field = new StringBuilder();
            if (at < line.length() && line.charAt(at) == '"') {
                int open = at++;
                while (true) {
                    if (at >= line.length()) {
                        throw new IllegalArgumentException("the quote at column " + (open + 1) + " is not closed");
                    }
                    char c = line.charAt(at++);
                    if (c != '"') {
                        field.append(c);
                    } else if (at < line.length() && line.charAt(at) == '"') {
                        field.append('"');
                        at++;
                    } else {
                        break;
                    }
                }
                while (at < line.length() && line.charAt(at) == ' ') {
                    at++;
                }
                if (at < line.length() && line.charAt(at) != ',') {
                    throw new IllegalArgumentException("column " + (at + 1) + ": a quoted field is followed by '"
                            + line.charAt(at) + "', not by a comma");
                }
            } else {
                int comma = line.indexOf(',', start);
                at = comma < 0 ? line.length() : comma;
                field.append(line, start, at);
                if (field.indexOf("\"") >= 0) {
                    throw new IllegalArgumentException("column " + (start + field.indexOf("\"") + 1) + ": a quote"
                            + " inside a field that does not start with one");
                }
            }
            fields.add(field.toString());
            if (at >= line.length()) {
                return fields;
            }
            at++; // the comma
        }
    }

    /**
     * The lines DTRON writes, read without the general parser: an object of strings without escapes, integers
     * that fit a long and one level of such objects, without spaces. {@link #parse} gives what {@link Json#parse}
     * gives for such a line, and null for any other line, which the general parser then reads (and explains).
     */
    static final class Flat {
        private final String text;
        private int at;

        private Flat(String text) {
            this.text = text;
        }

        /** The object of {@code line}, or null when it is not of the simple shape. */
        static Map<String, Object> parse(String line) {
            Flat f = new Flat(line);
            Map<String, Object> m = f.object(true);
            return m != null && f.at == line.length() ? m : null;
        }

        private Map<String, Object> object(boolean outer) {
            if (!next('{')) {
                return null;
            }
            Map<String, Object> map = new LinkedHashMap<>();
            if (next('}')) {
                return map;
            }
            do {
                String key = string();
                if (key == null || !next(':') || map.containsKey(key)) {
                    return null;
                }
                Object value;
                char c = at < text.length() ? text.charAt(at) : 0;
                if (c == '"') {
                    value = string();
                } else if (c == '{' && outer) {
                    value = object(false);
                } else {
                    value = integer();
                }
                if (value == null) {
                    return null;
                }
                map.put(key, value);
            } while (next(','));
            return next('}') ? map : null;
        }

        private boolean next(char c) {
            if (at < text.length() && text.charAt(at) == c) {
                at++;
                return true;
            }
            return false;
        }

        private String string() {
            if (!next('"')) {
                return null;
            }
            int start = at;
            for (; at < text.length(); at++) {
                char c = text.charAt(at);
                if (c == '"') {
                    return text.substring(start, at++);
                }
                if (c < 0x20 || c == '\\') {
                    return null;
                }
            }
            return null;
        }

        /** An integer of at most 18 digits, without a leading zero (but 0 itself), fraction or exponent. */
        private Long integer() {
            int start = at;
            next('-');
            int digits = at;
            long value = 0;
            while (at < text.length() && text.charAt(at) >= '0' && text.charAt(at) <= '9') {
                value = 10 * value + (text.charAt(at++) - '0');
            }
            int n = at - digits;
            if (n == 0 || n > 18 || n > 1 && text.charAt(digits) == '0' || at < text.length()
                    && (text.charAt(at) == '.' || text.charAt(at) == 'e' || text.charAt(at) == 'E')) {
                return null;
            }
            return text.charAt(start) == '-' ? -value : value;
        }
    }
}
