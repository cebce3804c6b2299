package io.dtron.cli;

import io.dtron.model.delta.DeltaExtension.Delay;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;

/**
 * The delay report of a run ({@code dtron run --delta-report FILE}): the delays measured per channel, which
 * {@code dtron delta --delta-from FILE} reads. Its JSON:
 *
 * <pre>
 * {"model": "ticker.xml", "timeUnitMicros": 10000, "runId": "3f2a9c",
 *  "channels": [{"channel": "reset", "direction": "input", "count": 11, "lowMicros": 180, "highMicros": 2400}, ...]}
 * </pre>
 *
 * {@code model} and {@code runId} may be left out; other keys are ignored. A channel with count 0 was not
 * measured.
 *
 * @param model          the model file the run tested, or null
 * @param timeUnitMicros the run's time unit in microseconds
 * @param runId          the run's id, or null
 * @param channels       the channels, in the order written
 */
record DeltaReport(String model, long timeUnitMicros, String runId, List<Channel> channels) {
    DeltaReport {
        channels = List.copyOf(channels);
    }

    /**
     * The delays of one channel in a run.
     *
     * @param channel    the channel's name on the bus
     * @param input      whether it is an input (else an output)
     * @param count      how many of its messages were measured
     * @param lowMicros  the shortest delay, in microseconds
     * @param highMicros the longest delay, in microseconds
     */
    record Channel(String channel, boolean input, long count, long lowMicros, long highMicros) {
    }

    /**
     * Reads a report's text.
     *
     * @throws IllegalArgumentException saying what is wrong and where, when it is no JSON or not of this shape
     */
    static DeltaReport parse(String text) {
        if (!(Json.parse(text) instanceof Map<?, ?> root)) {
            throw new IllegalArgumentException("the report is not a JSON object");
        }
        long unit = integer(root, "timeUnitMicros", "the report");
        if (unit <= 0) {
            throw new IllegalArgumentException("timeUnitMicros must be positive, not " + unit);
        }
        if (!(root.get("channels") instanceof List<?> list)) {
            throw new IllegalArgumentException("the report has no \"channels\" array");
        }
        Set<String> seen = new HashSet<>();
        List<Channel> channels = new ArrayList<>();
        for (int i = 0; i < list.size(); i++) {
            String where = "channels[" + i + "]";
            if (!(list.get(i) instanceof Map<?, ?> c)) {
                throw new IllegalArgumentException(where + " is not an object");
            }
            String name = string(c, "channel", where, true);
            if (name.isEmpty() || !seen.add(name)) {
                throw new IllegalArgumentException(where + ": " + (name.isEmpty() ? "the channel has no name"
                        : "channel '" + name + "' appears twice"));
            }
            where = "channel '" + name + "'";
            String direction = string(c, "direction", where, true);
            if (!direction.equals("input") && !direction.equals("output")) {
                throw new IllegalArgumentException(where + ": direction must be \"input\" or \"output\", not \""
                        + direction + "\"");
            }
            long count = integer(c, "count", where);
            long low = integer(c, "lowMicros", where);
            long high = integer(c, "highMicros", where);
            if (count < 0 || count > 0 && (low < 0 || high < low)) {
                throw new IllegalArgumentException(where + ": needs count >= 0 and, when measured, 0 <= lowMicros"
                        + " <= highMicros, not count " + count + ", " + low + ".." + high);
            }
            channels.add(new Channel(name, direction.equals("input"), count, low, high));
        }
        return new DeltaReport(string(root, "model", "the report", false), unit, string(root, "runId", "the report",
                false), channels);
    }

    /** The measured channels' delays (count above 0), by channel name, in the order written. */
    Map<String, Delay> measured() {
        Map<String, Delay> delays = new LinkedHashMap<>();
        for (Channel c : channels) {
            if (c.count() > 0) {
                delays.put(c.channel(), new Delay(c.lowMicros(), c.highMicros()));
            }
        }
        return delays;
    }

    private static long integer(Map<?, ?> object, String key, String where) {
        if (!(object.get(key) instanceof Long value)) {
            throw new IllegalArgumentException(where + ": \"" + key + "\" must be an integer"
                    + (object.containsKey(key) ? "" : ", and is missing"));
        }
        return value;
    }

    private static String string(Map<?, ?> object, String key, String where, boolean required) {
        Object value = object.get(key);
        if (value == null && !required && !object.containsKey(key)) {
            return null;
        }
        if (!(value instanceof String s)) {
            throw new IllegalArgumentException(where + ": \"" + key + "\" must be a string"
                    + (object.containsKey(key) ? "" : ", and is missing"));
        }
        return s;
    }
}
