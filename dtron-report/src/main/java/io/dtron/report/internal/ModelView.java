package io.dtron.report.internal;

import io.dtron.model.Layout;
import io.dtron.model.Network;
import io.dtron.model.Process;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * The model as the report draws it: each template's drawing (saved, or laid out by {@link AutoLayout} where the
 * model has no positions) and the processes that instantiate it; finds the edges a trace names ({@code Lamp: off ->
 * low i_press?}) as process and edge numbers.
 */
public final class ModelView {
    private final List<Layout.Template> templates = new ArrayList<>();
    private final List<Boolean> automatic = new ArrayList<>();
    private final List<Process> processes;
    private final Map<String, Integer> processByName = new HashMap<>();
    private final Map<String, Integer> templateByName = new LinkedHashMap<>();
    private final Map<String, int[]> resolved = new HashMap<>();
    private final String json;

    /** The view of {@code network} drawn with {@code layout}; either may be null (no model: nothing is drawn). */
    public ModelView(Network network, Layout layout) {
        this.processes = network == null ? List.of() : network.processes();
        if (layout != null) {
            for (Layout.Template t : layout.templates()) {
                boolean saved = t.positioned();
                templateByName.put(t.name(), templates.size());
                templates.add(saved ? t : AutoLayout.of(t));
                automatic.add(!saved);
            }
        }
        for (Process p : processes) {
            processByName.put(p.name(), p.index());
        }
        this.json = toJson();
    }

    /** The {@code "templates":[...],"processes":[...]} members of the page's data. */
    public String json() {
        return json;
    }

    /**
     * The process and edge numbers, flattened ({@code p, e, p, e...}), of the edges {@code descriptions} names;
     * an edge that several edges of one process match (the same source, target and label) names them all.
     */
    public int[] edges(List<String> descriptions) {
        int[] out = new int[8];
        int n = 0;
        for (String d : descriptions) {
            int[] found = resolved.computeIfAbsent(d, this::resolve);
            if (n + found.length > out.length) {
                out = java.util.Arrays.copyOf(out, Math.max(out.length * 2, n + found.length));
            }
            System.arraycopy(found, 0, out, n, found.length);
            n += found.length;
        }
        return java.util.Arrays.copyOf(out, n);
    }

    private int[] resolve(String description) {
        int colon = description.indexOf(": ");
        int arrow = description.indexOf(" -> ", colon + 2);
        if (colon < 0 || arrow < 0) {
            return new int[0];
        }
        Integer p = processByName.get(description.substring(0, colon));
        if (p == null) {
            return new int[0];
        }
        String source = description.substring(colon + 2, arrow);
        String rest = description.substring(arrow + 4);
        int space = rest.indexOf(' ');
        String target = space < 0 ? rest : rest.substring(0, space);
        String label = space < 0 ? "" : rest.substring(space + 1).replaceAll("\\s", "");
        Process process = processes.get(p);
        Integer t = templateByName.get(process.template());
        List<Integer> matches = new ArrayList<>();
        for (io.dtron.model.Edge e : process.edges()) {
            if (process.locations().get(e.source()).name().equals(source)
                    && process.locations().get(e.target()).name().equals(target)) {
                matches.add(e.index());
            }
        }
        if (matches.size() > 1 && t != null) {
            List<Integer> byLabel = matches.stream().filter(e -> e < templates.get(t).edges().size()
                    && sync(templates.get(t).edges().get(e)).equals(label)).toList();
            matches = byLabel.isEmpty() ? matches : byLabel;
        }
        int[] out = new int[matches.size() * 2];
        for (int i = 0; i < matches.size(); i++) {
            out[2 * i] = p;
            out[2 * i + 1] = matches.get(i);
        }
        return out;
    }

    private static String sync(Layout.Edge e) {
        return e.labels().stream().filter(l -> l.kind().equals("synchronisation")).map(l -> l.text()
                .replaceAll("\\s", "")).findFirst().orElse("");
    }

    private String toJson() {
        StringBuilder sb = new StringBuilder("\"templates\":[");
        for (int i = 0; i < templates.size(); i++) {
            Layout.Template t = templates.get(i);
            sb.append(i == 0 ? "" : ",").append("{\"name\":");
            JsonText.quote(t.name(), sb);
            sb.append(",\"auto\":").append(automatic.get(i)).append(",\"locations\":[");
            for (int l = 0; l < t.locations().size(); l++) {
                Layout.Location loc = t.locations().get(l);
                sb.append(l == 0 ? "" : ",").append("{\"name\":");
                JsonText.quote(loc.name(), sb);
                sb.append(",\"kind\":\"").append(loc.kind()).append("\",\"initial\":").append(loc.initial());
                point("at", loc.at(), sb);
                labels(loc.labels(), sb);
                sb.append('}');
            }
            sb.append("],\"edges\":[");
            for (int e = 0; e < t.edges().size(); e++) {
                Layout.Edge edge = t.edges().get(e);
                sb.append(e == 0 ? "" : ",").append("{\"source\":").append(edge.source()).append(",\"target\":")
                        .append(edge.target()).append(",\"nails\":[");
                for (int k = 0; k < edge.nails().size(); k++) {
                    Layout.Point n = edge.nails().get(k);
                    sb.append(k == 0 ? "" : ",").append('[').append(n.x()).append(',').append(n.y()).append(']');
                }
                sb.append(']');
                labels(edge.labels(), sb);
                sb.append('}');
            }
            sb.append("]}");
        }
        sb.append("],\"processes\":[");
        for (Process p : processes) {
            sb.append(p.index() == 0 ? "" : ",").append("{\"name\":");
            JsonText.quote(p.name(), sb);
            Integer t = templateByName.get(p.template());
            sb.append(",\"template\":").append(t == null ? -1 : t).append(",\"initial\":").append(p.initial())
                    .append(",\"locations\":[");
            for (int l = 0; l < p.locations().size(); l++) {
                sb.append(l == 0 ? "" : ",");
                JsonText.quote(p.locations().get(l).name(), sb);
            }
            sb.append("]}");
        }
        return sb.append(']').toString();
    }

    private static void point(String name, Layout.Point p, StringBuilder sb) {
        if (p != null) {
            sb.append(",\"").append(name).append("\":[").append(p.x()).append(',').append(p.y()).append(']');
        }
    }

    private static void labels(List<Layout.Label> labels, StringBuilder sb) {
        sb.append(",\"labels\":[");
        for (int i = 0; i < labels.size(); i++) {
            Layout.Label l = labels.get(i);
            sb.append(i == 0 ? "" : ",").append("{\"kind\":");
            JsonText.quote(l.kind(), sb);
            sb.append(",\"text\":");
            JsonText.quote(l.text(), sb);
            point("at", l.at(), sb);
            sb.append('}');
        }
        sb.append(']');
    }
}
