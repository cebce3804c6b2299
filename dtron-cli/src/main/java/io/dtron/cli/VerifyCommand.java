package io.dtron.cli;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.verify.CoverTime;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import io.dtron.engine.verify.SearchOrder;
import io.dtron.engine.verify.VerificationResult;
import io.dtron.engine.verify.VerificationResult.Outcome;
import io.dtron.engine.verify.Verifier;
import io.dtron.engine.verify.VerifierOptions;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/** {@code dtron verify MODEL}: checks the model's queries, or queries given, by symbolic model checking. */
@Command(name = "verify", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Check queries on a model by symbolic model checking: E<> p, A[] p, E[] p, A<> p, p --> q.",
                "The queries come from the model's <queries>, from --queries FILE.q, or from --query; queries that"
                        + " are not symbolic (Pr[...], simulate, sup:, control:, ...) are listed as skipped.",
                "Exit code 0 when every query checked holds, 2 when some does not, else 1 when a query is in error"
                        + " (each is reported, the others checked) or for any other error, else 3 when some could"
                        + " not be decided within the limits (inconclusive)."})
final class VerifyCommand implements Callable<Integer> {

    enum Order { bfs, dfs }

    enum Format { text, json, none }

    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The model file (.xml, .xta, .ta).")
    private Path model;

    @Option(names = "--query", paramLabel = "Q", description = "A query to check (repeatable); replaces the model's"
            + " own queries.")
    private List<String> queries = new ArrayList<>();

    @Option(names = "--queries", paramLabel = "FILE.q", description = "A file of queries, one per line; replaces the"
            + " model's own queries.")
    private Path queryFile;

    @Option(names = "--traps", description = "Check the coverage-correctness obligation instead of the model's queries:"
            + " every trap (a bool variable or array element named trap... or t_...) reachable, E<> each, and all of"
            + " them on one path, E<> all together (with --query and --queries: besides those); then the shortest"
            + " time in which a run sets them all.")
    private boolean traps;

    @Option(names = "--order", paramLabel = "bfs|dfs", defaultValue = "bfs", description = "Search order of"
            + " reachability queries: breadth-first (shortest traces, the default) or depth-first.")
    private Order order;

    @Option(names = "--trace", paramLabel = "text|json|none", defaultValue = "text", description = "How to print the"
            + " diagnostic trace of a query that has one (default: text). With json, standard output holds only the"
            + " traces, one JSON object a line, and the rest goes to standard error.")
    private Format traceFormat;

    @Option(names = "--time-limit", paramLabel = "SECONDS", description = "Give up a query after this long: its"
            + " answer is then unknown.")
    private Double timeLimit;
    /** The longest --time-limit: what a Duration of nanoseconds in a long holds. */
    private static final long MAX_TIME_LIMIT_SECONDS = 9_223_372_036L;

    @Option(names = "--memory-limit", paramLabel = "MB", description = "Give up a query when the heap in use"
            + " passes this many MB: its answer is then unknown.")
    private Long memoryLimit;

    /** With --delta or --delta-from: the Delta-extended model is checked (thesis 3.5, step 3). */
    @Mixin
    private DeltaDelays delays;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        try {
            return verify(out, err);
        } catch (ModelException e) {
            CheckCommand.printErrors(model, e, err);
            return 1;
        } catch (UnsupportedModelException | QueryException e) {
            err.println("dtron verify: " + model + ": " + e.getMessage());
            return 1;
        } catch (NoSuchFileException e) {
            err.println("dtron verify: " + e.getFile() + ": error: no such file");
            return 1;
        } catch (IOException e) {
            err.println("dtron verify: " + OutputFile.reason(e));
            return 1;
        } finally {
            out.flush();
            err.flush();
        }
    }

    private int verify(PrintWriter out, PrintWriter err) throws ModelException, IOException {
        // with JSON traces, standard output holds the JSON alone (one trace a line) and the text goes to stderr
        PrintWriter text = traceFormat == Format.json ? err : out;
        if (timeLimit != null && !(timeLimit >= 0 && timeLimit <= MAX_TIME_LIMIT_SECONDS)
                || memoryLimit != null && !(memoryLimit > 0 && memoryLimit <= Long.MAX_VALUE >> 20)) {
            err.println("dtron verify: --time-limit must be a number of seconds from 0 to " + MAX_TIME_LIMIT_SECONDS
                    + " (about 292 years) and --memory-limit a positive number of MB, at most "
                    + (Long.MAX_VALUE >> 20));
            return 1;
        }
        Network network;
        if (delays.given()) {
            network = deltaExtended(text, err);
            if (network == null) {
                return 1;
            }
        } else if (delays.strayOptions()) {
            err.println("dtron verify: --interface and --timeunit go with the delays of --delta or --delta-from");
            return 1;
        } else {
            network = ModelLoader.load(model);
        }
        VerifierOptions options = VerifierOptions.defaults()
                .withOrder(order == Order.dfs ? SearchOrder.DEPTH_FIRST : SearchOrder.BREADTH_FIRST)
                .withTimeLimit(timeLimit == null ? null : Duration.ofNanos((long) (timeLimit * 1e9)))
                .withMemoryLimit(memoryLimit == null ? 0 : memoryLimit << 20);
        Verifier verifier = null;
        UnsupportedModelException cannotRun = null;
        try {
            verifier = new Verifier(network, options);
        } catch (UnsupportedModelException e) {
            // a model of statistical model checking: its statistical queries are skipped as always, the others
            // cannot be checked, and each says so
            cannotRun = e;
        }
        List<Query> toCheck = new ArrayList<>();
        for (String q : queries) {
            try {
                toCheck.add(Query.parse(q));
            } catch (QueryException e) {
                toCheck.add(new Query(q.strip(), Query.Kind.INVALID, null, null, e.getMessage(), 0, 0));
            }
        }
        if (queryFile != null) {
            String queryText;
            try {
                queryText = Files.readString(queryFile, StandardCharsets.UTF_8);
            } catch (NoSuchFileException e) {
                throw e;
            } catch (IOException e) {
                err.println("dtron verify: cannot read " + queryFile + ": " + OutputFile.reason(e));
                return 1;
            }
            toCheck.addAll(Query.parseFile(queryText));
        }
        String source = "--query";
        if (queryFile != null) {
            source = queries.isEmpty() ? queryFile.toString() : "--query and " + queryFile;
        }
        List<String> trapNames = List.of();
        int firstTrap = -1;
        if (traps) {
            List<String> names = io.dtron.engine.coverage.Traps.of(network, List.of());
            trapNames = names;
            firstTrap = toCheck.size();
            if (names.isEmpty()) {
                err.println("dtron verify: " + model + " has no traps: bool variables or arrays whose name starts with"
                        + " trap or t_");
                return 1;
            }
            for (String t : names) {
                toCheck.add(Query.parse("E<> " + t));
            }
            if (names.size() > 1) {
                toCheck.add(Query.parse("E<> " + String.join(" and ", names)));
            }
            source = (toCheck.size() > names.size() + (names.size() > 1 ? 1 : 0) ? source + " and " : "") + "--traps ("
                    + names.size() + " trap" + (names.size() == 1 ? "" : "s") + ")";
        }
        if (toCheck.isEmpty()) {
            toCheck.addAll(verifier != null ? verifier.modelQueries() : modelQueries(network));
            source = "the model";
        }
        if (toCheck.isEmpty()) {
            err.println("dtron verify: " + model + " has no queries: give --query Q or --queries FILE.q");
            return 1;
        }
        text.println(model + ": " + toCheck.size() + " quer" + (toCheck.size() == 1 ? "y" : "ies") + " from " + source);
        int violated = 0;
        int unknown = 0;
        int skipped = 0;
        int errors = 0;
        List<String> unreachableTraps = new ArrayList<>();
        for (int i = 0; i < toCheck.size(); i++) {
            Query q = toCheck.get(i);
            text.println("[" + (i + 1) + "] " + q.text());
            if (cannotRun != null) {
                if (q.kind() == Query.Kind.UNSUPPORTED) {
                    text.println("    skipped: " + q.reason());
                    skipped++;
                } else {
                    text.println("    not checked: " + cannotRun.getMessage());
                    errors++;
                }
                continue;
            }
            VerificationResult r;
            try {
                r = verifier.verify(q);
            } catch (QueryException e) {
                Path where = q.line() > 0 ? queryFile : model;
                text.println("    error: " + e.getMessage());
                if (text != err) {
                    err.println("dtron verify: " + where + ": " + e.getMessage());
                }
                errors++;
                continue;
            } catch (UnsupportedModelException e) {
                // a model error met on this query's search (an index out of range, ...): the others are checked
                text.println("    error: " + e.getMessage());
                if (text != err) {
                    err.println("dtron verify: " + model + ": " + e.getMessage());
                }
                errors++;
                continue;
            }
            text.println("    " + line(r));
            if (firstTrap >= 0 && i >= firstTrap && i < firstTrap + trapNames.size()
                    && r.outcome() == Outcome.VIOLATED) {
                unreachableTraps.add(trapNames.get(i - firstTrap));
            }
            switch (r.outcome()) {
                case VIOLATED -> violated++;
                case UNKNOWN -> unknown++;
                case SKIPPED -> skipped++;
                default -> {
                }
            }
            String kind = r.outcome() == Outcome.SATISFIED ? "witness" : "counterexample";
            if (r.trace() != null && traceFormat == Format.json) {
                text.println("    " + kind + ": on standard output, JSON");
                out.println(r.trace().toJson());
            } else if (r.trace() != null && traceFormat == Format.text) {
                out.println("    " + kind + ":");
                out.print(r.trace().toText().replaceAll("(?m)^", "  "));
            }
            text.flush();
            out.flush();
        }
        if (cannotRun != null) {
            text.println("none checked: DTRON's engine cannot run the model" + (skipped > 0 ? "; " + skipped + " skipped"
                    : ""));
            err.println("dtron verify: " + model + ": " + cannotRun.getMessage());
            return 1;
        }
        if (traps) {
            text.println(fastestCover(verifier, trapNames, unreachableTraps));
        }
        int checked = toCheck.size() - skipped - errors;
        text.println(checked - violated - unknown + " of " + checked + " checked hold" + (violated > 0 ? ", " + violated
                + " do not" : "") + (unknown > 0 ? ", " + unknown + " unknown" : "") + (skipped > 0 ? "; " + skipped
                + " skipped" : "") + (errors > 0 ? "; " + errors + " in error" : ""));
        // a counterexample outranks an error, an error (to fix) an unknown answer (to retry with larger limits)
        return violated > 0 ? 2 : errors > 0 ? 1 : unknown > 0 ? 3 : 0;
    }

    /** The most symbolic states the search for the shortest time to set every trap explores. */
    static final long FASTEST_COVER_STATES = 200_000;

    /** The line on the shortest time to set every trap: searched when every trap is reachable on its own. */
    private static String fastestCover(Verifier verifier, List<String> names, List<String> unreachable) {
        if (!unreachable.isEmpty()) {
            return "no run sets every trap: " + String.join(", ", unreachable) + (unreachable.size() == 1 ? " is"
                    : " are") + " unreachable";
        }
        CoverTime t;
        try {
            t = verifier.fastestCover(names, FASTEST_COVER_STATES);
        } catch (QueryException | UnsupportedModelException e) {
            return "the shortest time to set every trap is unknown: " + e.getMessage();
        }
        return switch (t.answer()) {
            case FOUND -> "the shortest time to set every trap: " + (t.strict() ? "just over " : "") + t.units()
                    + " time unit" + (t.units() == 1 && !t.strict() ? "" : "s") + " (" + t.explored()
                    + " symbolic states explored)";
            case NONE -> "no run sets every trap (" + t.explored() + " symbolic states explored)";
            case UNKNOWN -> "the shortest time to set every trap is unknown: the search stopped at its limit of "
                    + FASTEST_COVER_STATES + " symbolic states";
        };
    }

    /** The queries written in {@code network}, parsed; one that does not parse is {@link Query.Kind#INVALID}. */
    private static List<Query> modelQueries(Network network) {
        List<Query> out = new ArrayList<>();
        for (io.dtron.xta.ast.Query q : network.queries()) {
            try {
                out.add(Query.parse(q.pos().text()));
            } catch (QueryException e) {
                out.add(new Query(q.pos().text().strip(), Query.Kind.INVALID, null, null, e.getMessage(), 0, 0));
            }
        }
        return out;
    }

    /** The Delta-extended model of the delays, loaded, or null after an error (printed). */
    private Network deltaExtended(PrintWriter out, PrintWriter err) throws ModelException {
        DeltaDelays.Extended extended;
        try {
            extended = delays.extend("verify", model, err);
        } catch (DeltaDelays.Refusal r) {
            err.println("dtron verify: " + r.getMessage());
            return null;
        }
        if (extended == null) {
            return null;
        }
        int widened = extended.result().changes().size();
        out.println("dtron verify: the Delta-extended model: " + widened + " clock bound" + (widened == 1 ? "" : "s")
                + " widened by " + extended.source() + " at " + extended.unitMicros() + " us per time unit"
                + " (dtron delta writes the same model to a file)");
        return extended.load(model);
    }

    private static String line(VerificationResult r) {
        VerificationResult.Statistics s = r.statistics();
        String figures = String.format(Locale.ROOT, "(%,d states explored, %,d stored, %.2f s, %d MB)", s.explored(),
                s.stored(), s.time().toNanos() / 1e9, s.memoryBytes() >> 20);
        return switch (r.outcome()) {
            case SATISFIED -> "satisfied " + figures;
            case VIOLATED -> "NOT satisfied " + figures;
            case UNKNOWN -> "unknown: " + r.reason() + " " + figures;
            case SKIPPED -> "skipped: " + r.reason();
        };
    }
}
