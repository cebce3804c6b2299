package io.dtron.report;

import io.dtron.engine.coverage.Coverage;
import io.dtron.model.Layout;
import io.dtron.model.Network;
import io.dtron.report.internal.JsonText;
import io.dtron.report.internal.ModelView;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.function.Consumer;

/**
 * What a report shows of one run: its settings, its inputs and outputs with the deadline the model set each
 * output and the window it allowed it in, the edges the tester committed to, the verdict and the coverage, with the
 * model's drawing. Filled as the run goes on ({@link RunRecorder}) or from a recorded trace; read as the page's data
 * ({@link #json()}), and, for the live view, as a stream of updates ({@link #onUpdate}). Thread-safe: the tester's
 * thread appends, other threads read; an append never waits for a reader.
 */
public final class RunRecord {
    /** The version of the page's data, its member {@code "report"}. */
    public static final int VERSION = 1;

    private final String model;
    private final ModelView view;
    private final String modelNote;
    private final List<String> events = new ArrayList<>();
    private final List<String> edges = new ArrayList<>();
    private String start = "null";
    private String verdict = "null";
    private String coverage = "null";
    private long seq;
    private long dueMicros = -1;
    /** The window the model allowed the next output in, -1 unknown; -1 for its end: open to the end of the test. */
    private long windowFrom = -1;
    private long windowUntil = -1;
    private volatile Consumer<String> sink;

    /**
     * A record of a run of {@code model}, drawn with {@code layout}.
     *
     * @param model     the model's file as the run named it
     * @param network   the loaded model, or null when it could not be loaded (nothing is drawn)
     * @param layout    its drawing, or null
     * @param modelNote why the model is not drawn, or null
     */
    public RunRecord(String model, Network network, Layout layout, String modelNote) {
        this.model = model;
        this.view = new ModelView(network, layout);
        this.modelNote = modelNote;
    }

    /**
     * Sends every later update, as one line of JSON ({@code {"seq":N,...}}), to {@code sink}, on the appending
     * thread: it must return at once.
     */
    public void onUpdate(Consumer<String> sink) {
        this.sink = sink;
    }

    /** The run's settings. */
    public void start(long seed, long timeUnitMicros, long timeout, boolean virtualTime) {
        String json = "{\"seed\":" + seed + ",\"timeunit_us\":" + timeUnitMicros + ",\"timeout\":" + timeout
                + ",\"virtual_time\":" + virtualTime + "}";
        synchronized (this) {
            start = json;
            publish("\"start\":" + json);
        }
    }

    /**
     * The tester waits, from {@code nowMicros}, for an output the model requires by {@code untilMicros} (the deadline
     * of the next output), or, when {@code untilMicros} is -1, for something else (its next input, the end).
     */
    public synchronized void due(long nowMicros, long untilMicros) {
        dueMicros = untilMicros;
    }

    /**
     * The model allowed the next output from {@code fromMicros} to {@code untilMicros} since the start, -1 when the
     * window stays open to the end of the test; its {@link #event} shows it beside it.
     */
    public synchronized void window(long fromMicros, long untilMicros) {
        windowFrom = fromMicros;
        windowUntil = untilMicros;
    }

    /**
     * An input applied ({@code input}) or an output observed at {@code micros}, with its values; an output with the
     * window the last {@link #window} gave, if any.
     */
    public void event(boolean input, long micros, String channel, Map<String, Integer> values) {
        StringBuilder sb = new StringBuilder(48).append('[').append(input ? 0 : 1).append(',').append(micros)
                .append(',');
        JsonText.quote(channel, sb);
        sb.append(',');
        JsonText.values(values, sb);
        synchronized (this) {
            // the deadline the model set for an output: the one of the wait it came in
            sb.append(',').append(input ? -1 : dueMicros).append(',').append(input ? -1 : windowFrom).append(',')
                    .append(input ? -1 : windowUntil).append(']');
            if (!input) {
                windowFrom = -1;
                windowUntil = -1;
            }
            String json = sb.toString();
            events.add(json);
            publish("\"event\":" + json);
        }
    }

    /** The edges the tester committed to at {@code micros}, as the tester names them. */
    public void edges(long micros, List<String> certainly, List<String> possibly) {
        StringBuilder sb = new StringBuilder(32).append('[').append(micros).append(',');
        int[] sure = view.edges(certainly);
        JsonText.ints(sure, sure.length, sb);
        sb.append(',');
        int[] maybe = view.edges(possibly);
        JsonText.ints(maybe, maybe.length, sb);
        String json = sb.append(']').toString();
        synchronized (this) {
            edges.add(json);
            publish("\"edges\":" + json);
        }
    }

    /** The verdict. */
    public void verdict(String verdict, String explanation, long micros, int inputs, int outputs) {
        StringBuilder sb = new StringBuilder("{\"verdict\":");
        JsonText.quote(verdict, sb);
        sb.append(",\"explanation\":");
        JsonText.quote(explanation, sb);
        sb.append(",\"t_us\":").append(micros).append(",\"inputs\":").append(inputs).append(",\"outputs\":")
                .append(outputs).append('}');
        synchronized (this) {
            this.verdict = sb.toString();
            publish("\"verdict\":" + this.verdict);
        }
    }

    /** What the run covered, as the model checker measured it. */
    public void coverage(Coverage c) {
        String json = coverageJson(c);
        synchronized (this) {
            coverage = json;
            publish("\"coverage\":" + json);
        }
    }

    /** How many inputs and outputs are recorded. */
    public synchronized int eventCount() {
        return events.size();
    }

    /** The page's data: one JSON object, the whole run so far, with the number of the last update it holds. */
    public String json() {
        List<String> ev;
        List<String> ed;
        String s;
        String v;
        String c;
        long n;
        synchronized (this) {
            ev = List.copyOf(events);
            ed = List.copyOf(edges);
            s = start;
            v = verdict;
            c = coverage;
            n = seq;
        }
        StringBuilder sb = new StringBuilder(64 + ev.size() * 48 + ed.size() * 32 + view.json().length());
        sb.append("{\"report\":").append(VERSION).append(",\"seq\":").append(n).append(",\"model\":");
        JsonText.quote(model, sb);
        sb.append(",\"model_note\":");
        sb.append(JsonText.quote(modelNote));
        sb.append(",\"start\":").append(s).append(',').append(view.json()).append(",\"events\":[");
        for (int i = 0; i < ev.size(); i++) {
            sb.append(i == 0 ? "" : ",\n").append(ev.get(i));
        }
        sb.append("],\"edges\":[");
        for (int i = 0; i < ed.size(); i++) {
            sb.append(i == 0 ? "" : ",\n").append(ed.get(i));
        }
        return sb.append("],\"verdict\":").append(v).append(",\"coverage\":").append(c).append("}").toString();
    }

    /** Numbers an update and hands it to the sink; called holding the lock, so updates keep their order. */
    private void publish(String member) {
        seq++;
        Consumer<String> s = sink;
        if (s != null) {
            s.accept("{\"seq\":" + seq + "," + member + "}");
        }
    }

    private static String coverageJson(Coverage c) {
        StringBuilder sb = new StringBuilder("{\"summary\":");
        JsonText.quote(c.summary(), sb);
        sb.append(",\"locations\":").append(figure(c.locations())).append(",\"edges\":").append(figure(c.edges()))
                .append(",\"traps\":").append(figure(c.trapFigure())).append(",\"edges_possibly\":")
                .append(c.edgesPossiblyTaken()).append(",\"processes\":{");
        for (int i = 0; i < c.processes().size(); i++) {
            Coverage.ProcessCoverage p = c.processes().get(i);
            sb.append(i == 0 ? "" : ",");
            JsonText.quote(p.name(), sb);
            sb.append(":{\"environment\":").append(p.environment()).append(",\"locations\":[");
            for (int l = 0; l < p.locations().size(); l++) {
                Coverage.LocationCoverage loc = p.locations().get(l);
                sb.append(l == 0 ? "" : ",").append('[').append(loc.taken().ordinal()).append(',')
                        .append(loc.reach().coverable() ? 1 : 0).append(']');
            }
            sb.append("],\"edges\":[");
            for (int e = 0; e < p.edges().size(); e++) {
                Coverage.EdgeCoverage edge = p.edges().get(e);
                sb.append(e == 0 ? "" : ",").append('[').append(edge.taken().ordinal()).append(',')
                        .append(edge.reach().coverable() ? 1 : 0).append(']');
            }
            sb.append("]}");
        }
        sb.append("},\"traps_list\":[");
        for (int t = 0; t < c.traps().size(); t++) {
            Coverage.Trap trap = c.traps().get(t);
            sb.append(t == 0 ? "" : ",").append('[');
            JsonText.quote(trap.name(), sb);
            sb.append(',').append(trap.set().ordinal()).append(']');
        }
        return sb.append("]}").toString();
    }

    private static String figure(Coverage.Figure f) {
        return "[" + f.covered() + "," + f.total() + "]";
    }
}
