package io.dtron.cli;

import io.dtron.engine.coverage.Coverage;
import io.dtron.model.Layout;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.report.ReportPage;
import io.dtron.report.RunRecord;
import java.io.BufferedReader;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron report TRACE.jsonl -o FILE.html}: the report of a recorded run, the page {@code dtron run --report}
 * writes, from the trace of {@code dtron run --trace}. The model is read from where the trace's start line names it
 * (as given, else beside the trace), or from {@code --model}.
 */
@Command(name = "report", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1,
        exitCodeOnExecutionException = 1,
        description = {"Make the HTML report of a run from its trace (dtron run --trace): the page dtron run --report"
                + " writes.", "Exit code 0 when written, 1 when the trace cannot be read."})
final class ReportCommand implements Callable<Integer> {
    private static final String COVERAGE_LINE = "{\"kind\":\"coverage\",\"coverage\":";
    private static final String EDGES_LINE = "{\"kind\":\"edges\",\"t_us\":";
    private static final String EDGE_LISTS = ",\"certainly\":";
    /** How many different lists of edges are kept parsed: a run's commitments repeat. */
    private static final int EDGE_LISTS_KEPT = 20_000;

    /** The edges lists of the trace's {@code edges} lines, parsed, by their text. */
    private final java.util.Map<String, List<List<String>>> edgeLists = new java.util.HashMap<>();

    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "TRACE.jsonl", description = "The trace of dtron run --trace.")
    private Path trace;

    @Option(names = {"-o", "--output"}, paramLabel = "FILE.html", required = true,
            description = "Where to write the report.")
    private Path output;

    @Option(names = "--model", paramLabel = "MODEL",
            description = "The model of the run (default: the file the trace names, as given or beside the trace).")
    private Path model;

    /** The model the report draws, and its file; null when it was not found or does not load. */
    private Network loaded;
    private Path loadedFile;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        RunRecord record;
        try {
            record = read(err);
        } catch (NoSuchFileException e) {
            err.println("dtron report: " + trace + ": no such file");
            return 1;
        } catch (IOException e) {
            err.println("dtron report: cannot read " + trace + ": " + OutputFile.reason(e));
            return 1;
        } catch (IllegalArgumentException e) {
            err.println("dtron report: " + e.getMessage());
            return 1;
        }
        try {
            ReportPage.write(record, output);
        } catch (IOException e) {
            err.println("dtron report: cannot write " + output + ": " + OutputFile.reason(e));
            return 1;
        }
        out.println("dtron report: " + record.eventCount() + " inputs and outputs of " + trace + " written to "
                + output);
        out.flush();
        return 0;
    }

    /** The run of the trace; the model is loaded when its start line comes. */
    private RunRecord read(PrintWriter err) throws IOException {
        RunRecord record = null;
        int number = 0;
        try (BufferedReader in = Files.newBufferedReader(trace, StandardCharsets.UTF_8)) {
            for (String line = in.readLine(); line != null; line = in.readLine()) {
                number++;
                if (line.isBlank()) {
                    continue;
                }
                String where = trace + " line " + number + ": ";
                if (line.startsWith(COVERAGE_LINE) && record != null) {
                    Coverage coverage;
                    try {
                        coverage = CoverageJson.read(line.substring(COVERAGE_LINE.length(), line.length() - 1));
                    } catch (IllegalArgumentException e) {
                        throw new IllegalArgumentException(where + "the coverage: " + e.getMessage());
                    }
                    sameModel(coverage);
                    record.coverage(coverage);
                    continue;
                }
                if (line.startsWith(EDGES_LINE) && record != null && edges(line, record, where)) {
                    continue;
                }
                Map<?, ?> o;
                try {
                    o = Json.parse(line) instanceof Map<?, ?> m ? m : null;
                } catch (IllegalArgumentException e) {
                    // the line is the parser's whole text: its place is a column
                    throw new IllegalArgumentException(where + "not JSON: " + e.getMessage()
                            .replaceFirst("^line 1, column", "column"));
                }
                Object kind = o == null ? null : o.get("kind");
                if (!(kind instanceof String)) {
                    throw new IllegalArgumentException(where + "not a line of a trace (no \"kind\")");
                }
                if (kind.equals("start")) {
                    record = start(o, where, err);
                    continue;
                }
                if (record == null) {
                    throw new IllegalArgumentException(where + "not a trace of dtron run: it does not begin with its"
                            + " start line");
                }
                switch ((String) kind) {
                    case "input", "output" -> {
                        if (o.containsKey("allowed_from_us")) {
                            // traces before the windows were recorded have none
                            record.window(number(o, "allowed_from_us", where), number(o, "allowed_until_us", where));
                        }
                        record.event(kind.equals("input"), number(o, "t_us", where), string(o, "channel", where),
                                values(o, where));
                    }
                    case "due" -> record.due(number(o, "t_us", where), number(o, "until_us", where));
                    case "edges" -> record.edges(number(o, "t_us", where), strings(o, "certainly", where),
                            strings(o, "possibly", where));
                    case "verdict" -> record.verdict(string(o, "verdict", where), string(o, "explanation", where),
                            number(o, "t_us", where), (int) number(o, "inputs", where),
                            (int) number(o, "outputs", where));
                    default -> {
                        // bus lines, and kinds of later versions: not part of the report
                    }
                }
            }
        }
        if (record == null) {
            throw new IllegalArgumentException(trace + " is not a trace of dtron run: it has no start line");
        }
        return record;
    }

    /**
     * An {@code edges} line as {@code dtron run --trace} writes it, read without parsing its lists again when an
     * earlier line had the same (a long run takes the same edges again and again); false when it is written otherwise
     * (then it is read as any line).
     */
    private boolean edges(String line, RunRecord record, String where) {
        int comma = line.indexOf(',', EDGES_LINE.length());
        int lists = line.indexOf(EDGE_LISTS, Math.max(comma, 0));
        if (comma < 0 || lists < 0 || !line.endsWith("}")) {
            return false;
        }
        long micros;
        try {
            micros = Long.parseLong(line, EDGES_LINE.length(), comma, 10);
        } catch (NumberFormatException e) {
            return false;
        }
        String text = line.substring(lists + 1, line.length() - 1);
        List<List<String>> parsed = edgeLists.get(text);
        if (parsed == null) {
            Map<?, ?> o;
            try {
                o = (Map<?, ?>) Json.parse("{" + text + "}");
            } catch (IllegalArgumentException | ClassCastException e) {
                return false;
            }
            parsed = List.of(strings(o, "certainly", where), strings(o, "possibly", where));
            if (edgeLists.size() < EDGE_LISTS_KEPT) {
                edgeLists.put(text, parsed);
            }
        }
        record.edges(micros, parsed.get(0), parsed.get(1));
        return true;
    }

    private RunRecord start(Map<?, ?> o, String where, PrintWriter err) {
        String named = string(o, "model", where);
        Path file = model != null ? model : locate(named);
        Network network = null;
        Layout layout = null;
        String note = null;
        if (file == null) {
            note = "the model " + named + " was not found (as given, or beside the trace): give it with --model";
        } else {
            try {
                network = ModelLoader.load(file);
                layout = Layout.read(file);
            } catch (ModelException e) {
                note = "the model " + file + " does not load: " + e.getMessage().lines().findFirst().orElse("");
            }
        }
        if (note != null) {
            err.println("dtron report: warning: " + note + "; the report shows the run without the model");
            err.flush();
        }
        loaded = network;
        loadedFile = file;
        RunRecord record = new RunRecord(named, network, layout, note);
        record.start(number(o, "seed", where), number(o, "timeunit_us", where), number(o, "timeout", where),
                Boolean.TRUE.equals(o.get("virtual_time")));
        return record;
    }

    /**
     * Refuses a model that is not the one of the run, by the fingerprint its coverage line recorded (a trace without
     * one, of TRON's backend, cannot be checked): the drawing would show another model's edges as covered.
     */
    private void sameModel(Coverage coverage) {
        if (loaded == null) {
            return;
        }
        String fingerprint = Coverage.fingerprintOf(loaded);
        if (!fingerprint.equals(coverage.fingerprint())) {
            throw new IllegalArgumentException(loadedFile + " is not the model of the run of " + trace + ": the run's"
                    + " model was " + coverage.model() + ", fingerprint " + coverage.fingerprint() + ", not "
                    + fingerprint + (model == null ? "; give the run's model with --model" : ""));
        }
    }

    /** The trace's model as given (relative to the working folder), else beside the trace; null if neither. */
    private Path locate(String named) {
        Path given = Path.of(named);
        if (Files.isRegularFile(given)) {
            return given;
        }
        Path folder = trace.toAbsolutePath().getParent();
        Path beside = folder == null ? null : folder.resolve(given.getFileName().toString());
        return beside != null && Files.isRegularFile(beside) ? beside : null;
    }

    private static long number(Map<?, ?> o, String name, String where) {
        if (o.get(name) instanceof Long n) {
            return n;
        }
        throw new IllegalArgumentException(where + "\"" + name + "\" is missing or not a whole number");
    }

    private static String string(Map<?, ?> o, String name, String where) {
        if (o.get(name) instanceof String s) {
            return s;
        }
        throw new IllegalArgumentException(where + "\"" + name + "\" is missing or not a string");
    }

    private static List<String> strings(Map<?, ?> o, String name, String where) {
        List<String> out = new ArrayList<>();
        if (o.get(name) instanceof List<?> l) {
            for (Object x : l) {
                if (!(x instanceof String s)) {
                    throw new IllegalArgumentException(where + "\"" + name + "\" holds a value that is not a string");
                }
                out.add(s);
            }
            return out;
        }
        throw new IllegalArgumentException(where + "\"" + name + "\" is missing or not a list");
    }

    private static Map<String, Integer> values(Map<?, ?> o, String where) {
        Map<String, Integer> out = new LinkedHashMap<>();
        if (!(o.get("values") instanceof Map<?, ?> m)) {
            throw new IllegalArgumentException(where + "\"values\" is missing or not an object");
        }
        for (Map.Entry<?, ?> e : m.entrySet()) {
            if (!(e.getValue() instanceof Long n) || n < Integer.MIN_VALUE || n > Integer.MAX_VALUE) {
                throw new IllegalArgumentException(where + "the value of " + e.getKey() + " is not an int");
            }
            out.put((String) e.getKey(), n.intValue());
        }
        return out;
    }
}
