package io.dtron.cli;

import io.dtron.engine.coverage.Coverage;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;

/**
 * The coverage file ({@code dtron run --coverage FILE.json}, {@code dtron coverage merge}): one JSON object, its
 * schema on the site's coverage page. The figures and the summary are written for readers; reading takes the
 * elements and works the figures out again.
 */
final class CoverageJson {
    /** The version of the schema, the value of {@code dtron_coverage}. */
    static final int VERSION = 1;

    private CoverageJson() {
    }

    /** {@code c} as the coverage file's text. */
    static String write(Coverage c) {
        StringBuilder sb = new StringBuilder("{\n");
        sb.append("  \"dtron_coverage\": ").append(VERSION).append(",\n");
        sb.append("  \"model\": ").append(JsonTrace.quote(c.model())).append(",\n");
        sb.append("  \"fingerprint\": ").append(JsonTrace.quote(c.fingerprint())).append(",\n");
        sb.append("  \"seeds\": ").append(c.seeds()).append(",\n");
        sb.append("  \"reachability\": ").append(c.reachabilityNote() == null ? "null"
                : JsonTrace.quote(c.reachabilityNote())).append(",\n");
        sb.append("  \"summary\": ").append(JsonTrace.quote(c.summary())).append(",\n");
        sb.append("  \"figures\": {\"locations\": ").append(figure(c.locations())).append(", \"edges\": ")
                .append(figure(c.edges())).append(", \"environment_edges\": ").append(figure(c.edges(true)))
                .append(", \"implementation_edges\": ").append(figure(c.edges(false)))
                .append(", \"edges_possibly\": ").append(c.edgesPossiblyTaken()).append(", \"traps\": ")
                .append(figure(c.trapFigure())).append("},\n");
        sb.append("  \"processes\": [");
        for (int i = 0; i < c.processes().size(); i++) {
            Coverage.ProcessCoverage p = c.processes().get(i);
            sb.append(i == 0 ? "\n" : ",\n").append("    {\"name\": ").append(JsonTrace.quote(p.name()))
                    .append(", \"template\": ").append(JsonTrace.quote(p.template())).append(", \"part\": \"")
                    .append(p.environment() ? "environment" : "implementation").append("\",\n     \"locations\": [");
            for (int l = 0; l < p.locations().size(); l++) {
                Coverage.LocationCoverage loc = p.locations().get(l);
                sb.append(l == 0 ? "\n" : ",\n").append("      {\"name\": ").append(JsonTrace.quote(loc.name()))
                        .append(", \"line\": ").append(loc.line()).append(", \"reach\": ").append(word(loc.reach()))
                        .append(", \"taken\": ").append(word(loc.taken())).append('}');
            }
            sb.append("],\n     \"edges\": [");
            for (int e = 0; e < p.edges().size(); e++) {
                Coverage.EdgeCoverage edge = p.edges().get(e);
                sb.append(e == 0 ? "\n" : ",\n").append("      {\"index\": ").append(edge.index())
                        .append(", \"source\": ").append(JsonTrace.quote(edge.source())).append(", \"target\": ")
                        .append(JsonTrace.quote(edge.target())).append(", \"label\": ")
                        .append(JsonTrace.quote(edge.label())).append(", \"line\": ").append(edge.line())
                        .append(", \"reach\": ").append(word(edge.reach())).append(", \"taken\": ")
                        .append(word(edge.taken())).append('}');
            }
            sb.append("]}");
        }
        sb.append("],\n  \"traps\": [");
        for (int t = 0; t < c.traps().size(); t++) {
            Coverage.Trap trap = c.traps().get(t);
            sb.append(t == 0 ? "" : ", ").append("{\"name\": ").append(JsonTrace.quote(trap.name()))
                    .append(", \"set\": ").append(word(trap.set())).append('}');
        }
        sb.append("],\n  \"channels\": [");
        for (int i = 0; i < c.channels().size(); i++) {
            Coverage.ChannelCoverage ch = c.channels().get(i);
            sb.append(i == 0 ? "\n" : ",\n").append("    {\"name\": ").append(JsonTrace.quote(ch.name()))
                    .append(", \"direction\": \"").append(ch.input() ? "input" : "output").append("\", \"count\": ")
                    .append(ch.count()).append(", \"values\": [");
            for (int v = 0; v < ch.values().size(); v++) {
                sb.append(v == 0 ? "" : ", ").append('{');
                boolean first = true;
                for (Map.Entry<String, Integer> e : ch.values().get(v).entrySet()) {
                    sb.append(first ? "" : ", ").append(JsonTrace.quote(e.getKey())).append(": ").append(e.getValue());
                    first = false;
                }
                sb.append('}');
            }
            sb.append("], \"more_values\": ").append(ch.moreValues()).append('}');
        }
        return sb.append("]\n}\n").toString();
    }

    private static String figure(Coverage.Figure f) {
        return "{\"covered\": " + f.covered() + ", \"coverable\": " + f.total() + "}";
    }

    private static String word(Enum<?> e) {
        return "\"" + e.name().toLowerCase(Locale.ROOT) + "\"";
    }

    /**
     * The coverage of a coverage file's text.
     *
     * @throws IllegalArgumentException when it is not JSON or not a coverage file, saying where
     */
    static Coverage read(String text) {
        Object root = Json.parse(text);
        Map<String, Object> o = object(root, "the file");
        Object version = o.get("dtron_coverage");
        if (!(version instanceof Long n) || n != VERSION) {
            throw new IllegalArgumentException("not a DTRON coverage file of version " + VERSION
                    + " (no \"dtron_coverage\": " + VERSION + ")");
        }
        List<Long> seeds = new ArrayList<>();
        for (Object s : list(o.get("seeds"), "seeds")) {
            seeds.add(number(s, "a seed"));
        }
        List<Coverage.ProcessCoverage> processes = new ArrayList<>();
        for (Object po : list(o.get("processes"), "processes")) {
            Map<String, Object> p = object(po, "a process");
            String name = string(p.get("name"), "a process's name");
            List<Coverage.LocationCoverage> locations = new ArrayList<>();
            for (Object lo : list(p.get("locations"), "the locations of " + name)) {
                Map<String, Object> l = object(lo, "a location of " + name);
                locations.add(new Coverage.LocationCoverage(string(l.get("name"), "a location's name"),
                        (int) number(l.get("line"), "a line"), value(Coverage.Reach.class, l.get("reach")),
                        value(Coverage.Taken.class, l.get("taken"))));
            }
            List<Coverage.EdgeCoverage> edges = new ArrayList<>();
            for (Object eo : list(p.get("edges"), "the edges of " + name)) {
                Map<String, Object> e = object(eo, "an edge of " + name);
                edges.add(new Coverage.EdgeCoverage((int) number(e.get("index"), "an edge's index"),
                        string(e.get("source"), "an edge's source"), string(e.get("target"), "an edge's target"),
                        string(e.get("label"), "an edge's label"), (int) number(e.get("line"), "a line"),
                        value(Coverage.Reach.class, e.get("reach")), value(Coverage.Taken.class, e.get("taken"))));
            }
            processes.add(new Coverage.ProcessCoverage(name, string(p.get("template"), "a template"),
                    "environment".equals(p.get("part")), locations, edges));
        }
        List<Coverage.Trap> traps = new ArrayList<>();
        for (Object to : list(o.get("traps"), "traps")) {
            Map<String, Object> t = object(to, "a trap");
            traps.add(new Coverage.Trap(string(t.get("name"), "a trap's name"),
                    value(Coverage.Taken.class, t.get("set"))));
        }
        List<Coverage.ChannelCoverage> channels = new ArrayList<>();
        for (Object co : list(o.get("channels"), "channels")) {
            Map<String, Object> ch = object(co, "a channel");
            List<Map<String, Integer>> values = new ArrayList<>();
            for (Object vo : list(ch.get("values"), "a channel's values")) {
                Map<String, Integer> v = new LinkedHashMap<>();
                object(vo, "a channel's value").forEach((k, x) -> v.put(k, (int) number(x, "a value")));
                values.add(v);
            }
            channels.add(new Coverage.ChannelCoverage(string(ch.get("name"), "a channel's name"),
                    "input".equals(ch.get("direction")), number(ch.get("count"), "a count"), values,
                    Boolean.TRUE.equals(ch.get("more_values"))));
        }
        Object note = o.get("reachability");
        return new Coverage(string(o.get("model"), "model"), string(o.get("fingerprint"), "fingerprint"), seeds,
                processes, traps, channels, note == null ? null : string(note, "reachability"));
    }

    @SuppressWarnings("unchecked")
    private static Map<String, Object> object(Object o, String what) {
        if (o instanceof Map<?, ?> m) {
            return (Map<String, Object>) m;
        }
        throw new IllegalArgumentException(what + " is not a JSON object");
    }

    private static List<?> list(Object o, String what) {
        if (o instanceof List<?> l) {
            return l;
        }
        throw new IllegalArgumentException(what + " is missing or not a JSON array");
    }

    private static String string(Object o, String what) {
        if (o instanceof String s) {
            return s;
        }
        throw new IllegalArgumentException(what + " is missing or not a string");
    }

    private static long number(Object o, String what) {
        if (o instanceof Long l) {
            return l;
        }
        throw new IllegalArgumentException(what + " is missing or not a whole number");
    }

    private static <E extends Enum<E>> E value(Class<E> type, Object o) {
        if (o instanceof String s) {
            for (E e : type.getEnumConstants()) {
                if (e.name().equalsIgnoreCase(s)) {
                    return e;
                }
            }
        }
        throw new IllegalArgumentException("'" + o + "' is not one of " + java.util.Arrays.toString(
                type.getEnumConstants()).toLowerCase(Locale.ROOT));
    }
}
