package io.dtron.cli;

import io.dtron.engine.GoalStatus;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.Steering;
import io.dtron.engine.SteeringReport;
import io.dtron.engine.TestOptions;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.engine.sim.Mutant;
import io.dtron.engine.sim.MutationReport;
import io.dtron.engine.sim.Mutants;
import io.dtron.engine.verify.QueryException;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Set;
import java.util.concurrent.Callable;
import java.util.stream.Collectors;
import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron mutants MODEL}: mutation analysis. Derives mutants of the model's implementation part, runs the
 * tester (with {@code dtron run}'s options for choosing inputs) against each mutant as the system under test in
 * virtual time, and prints a table of the mutants and the mutation score.
 */
@Command(name = "mutants", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Mutation analysis: run the tester against mutants of the model's implementation part.",
                "Each mutant is the model with one change to a process of the implementation (a guard or invariant"
                        + " bound moved by one, an output dropped, made early or late or given a wrong value, an urgent"
                        + " or committed location made ordinary), simulated as the system under test in virtual time"
                        + " for --budget time units with each of --seeds seeds (from --seed on) until a run FAILS."
                        + " Mutants whose change takes effect only at a location the checker proves unreachable are"
                        + " equivalent; mutants the engine refuses are invalid; neither counts in the score.",
                "Options of dtron run that choose inputs (--seed, --timeunit, --delay-policy, --delay-bound,"
                        + " --strategy, --goal, --horizon, ...) are passed to every run: --strategy coverage or goal"
                        + " steers each run as dtron run would.",
                "Exit code 0 when the analysis ran (whatever the score), 3 when the model as its own system does"
                        + " not PASS with every seed, 1 usage or model error."})
final class MutantsCommand implements Callable<Integer> {
    /** Options of dtron run that name a system under test, a bus or a file of one run: not for mutants. */
    private static final Set<String> NOT_FOR_MUTANTS = Set.of("--sut", "--sut-seed", "--classpath", "--cluster",
            "--bind", "--members", "--port", "--port-range", "--testers", "--join", "--key-file", "--insecure",
            "--wait-for-adapters", "--wait-timeout", "--adapter", "--tron-adapter", "--backend", "--delta", "--trace",
            "--trace-max-size",
            "--delta-report", "--delta-from", "--bus", "--timeout", "--report", "--live");
    /** Options of dtron run about one run's coverage: mutants are killed or survive, their runs' coverage is not kept. */
    private static final Set<String> COVERAGE_OF_ONE_RUN = Set.of("--coverage", "--until", "--traps",
            "--coverage-budget");

    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The model (.xml, .xta, or an Uppaal 3 .ta).")
    private Path model;

    @Option(names = "--interface", paramLabel = "FILE.trn",
            description = "Take inputs and outputs from a TRON interface file instead of the i_/o_ names.")
    private Path interfaceFile;

    @Option(names = "--budget", paramLabel = "UNITS",
            description = "Model time units of each run (default: the interface file's timeout, else 1000).")
    private Long budget;

    @Option(names = "--seeds", paramLabel = "N", defaultValue = "5",
            description = "Runs per mutant at most, with seeds --seed, --seed + 1, ... (default: 5).")
    private int seeds;

    @Option(names = "--threads", paramLabel = "N",
            description = "Mutants run at once (default: the available processors).")
    private Integer threads;

    @Option(names = "--check-time", paramLabel = "SECONDS", defaultValue = "10",
            description = "Time limit of the checker's search for each location a mutant changes (default: 10).")
    private long checkSeconds;

    @Option(names = "--json", paramLabel = "FILE", description = "Write the mutants and their results as JSON to FILE.")
    private Path json;

    @Option(names = "--junit", paramLabel = "FILE.xml",
            description = "Write the analysis as a JUnit XML report to FILE.xml: one test case per mutant (killed"
                    + " passes, survived fails, equivalent and invalid are skipped) and one for the model as its own"
                    + " system (an error unless it PASSED with every seed); the score and the seeds as properties.")
    private Path junit;

    @CommandLine.Unmatched
    private List<String> runOptions = new ArrayList<>();

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        RunCommand run = runCommand();
        if (seeds < 1) {
            throw usage("--seeds must be at least 1: " + seeds);
        }
        int threadCount = threads == null ? Runtime.getRuntime().availableProcessors() : threads;
        if (threadCount < 1) {
            throw usage("--threads must be at least 1: " + threadCount);
        }
        if (budget != null && budget <= 0) {
            throw usage("--budget must be a positive number of time units: " + budget);
        }
        if (checkSeconds <= 0) {
            throw usage("--check-time must be a positive number of seconds: " + checkSeconds);
        }
        for (String problem : new String[] {OutputFile.problem("--junit", junit, model, interfaceFile),
                OutputFile.problem("--json", json, model, interfaceFile)}) {
            if (problem != null) {
                throw usage(problem);
            }
        }
        CommandModel.Loaded loaded = CommandModel.load("mutants", model, interfaceFile, err);
        if (loaded == null) {
            return 1;
        }
        Network network = loaded.network();
        TestInterface testInterface = loaded.testInterface();
        if (testInterface.inputs().isEmpty() && testInterface.outputs().isEmpty()) {
            err.println("dtron mutants: " + model + " has no inputs or outputs: name channels i_x / o_y, or give"
                    + " --interface FILE.trn");
            return 1;
        }
        TestOptions options;
        Steering steering;
        try {
            steering = run.steering();
            options = run.testOptions(testInterface);
            options = options.withTimeout(budget != null ? budget : options.timeout()).withVirtualTime(true);
        } catch (ParameterException e) {
            throw usage(e.getMessage().replaceFirst("^dtron run: ", ""));
        } catch (IllegalArgumentException e) {
            throw usage(e.getMessage());
        }
        if (steering != null && !steerable(network, testInterface, options, steering, out)) {
            return 1;
        }
        List<Mutant> mutants;
        MutationReport report;
        try {
            mutants = Mutants.derive(network, testInterface, Duration.ofSeconds(checkSeconds));
            out.println("dtron mutants: " + model + ", " + mutants.size() + " mutants of the implementation, seeds "
                    + options.seed() + (seeds > 1 ? ".." + (options.seed() + seeds - 1) : "") + ", "
                    + options.timeout() + " time units each, delay policy "
                    + options.delayPolicy().name().toLowerCase(Locale.ROOT).replace('_', '-')
                    + (steering == null ? "" : ", strategy " + steering.strategy().name().toLowerCase(Locale.ROOT)));
            out.flush();
            report = Mutants.run(network, testInterface, mutants, options, steering, seeds, threadCount);
        } catch (UnsupportedModelException e) {
            err.println("dtron mutants: " + model + ": " + e.getMessage());
            return 1;
        }
        printTable(report, out);
        printSummary(report, threadCount, out);
        if (json != null) {
            try {
                Files.writeString(json, json(report, options, steering), StandardCharsets.UTF_8);
            } catch (IOException e) {
                err.println("dtron mutants: cannot write " + json + ": " + OutputFile.reason(e));
                return 1;
            }
        }
        if (junit != null) {
            try {
                writeJunit(report, options, steering, threadCount);
            } catch (IOException e) {
                err.println("dtron mutants: cannot write the JUnit report " + junit + ": " + OutputFile.reason(e));
                return 1;
            }
        }
        return report.modelRuns() == report.seeds().size() ? 0 : 3;
    }

    /**
     * Explores the model for the planner of {@code steering} before the mutants are derived: a goal that does not
     * compile is a usage error; a goal the checker proves unreachable is said (every run then ends INCONCLUSIVE).
     */
    private boolean steerable(Network network, TestInterface testInterface, TestOptions options, Steering steering,
                              PrintWriter out) {
        OnlineTester probe;
        try {
            probe = new OnlineTester(network, testInterface, new ModelSystem(network, testInterface, 0), options)
                    .steer(steering);
        } catch (QueryException e) {
            throw usage("--goal: " + e.getMessage());
        } catch (UnsupportedModelException e) {
            spec.commandLine().getErr().println("dtron mutants: " + model + ": " + e.getMessage());
            return false;
        }
        SteeringReport report = probe.steeringReport();
        for (GoalStatus g : report.goals()) {
            if (g.state() == GoalStatus.State.UNREACHABLE) {
                out.println("dtron mutants: goal '" + g.text() + "' is unreachable: " + g.reason()
                        + "; every run ends INCONCLUSIVE");
            }
        }
        return true;
    }

    /** dtron run's command line for the options this command does not take itself. */
    private RunCommand runCommand() {
        RunCommand run = new RunCommand();
        CommandLine line = new CommandLine(run);
        List<String> args = new ArrayList<>();
        args.add(model.toString());
        args.addAll(runOptions);
        CommandLine.ParseResult parsed;
        try {
            parsed = line.parseArgs(args.toArray(String[]::new));
        } catch (ParameterException e) {
            throw usage(e.getMessage().replaceFirst("^dtron run: ", ""));
        }
        for (CommandLine.Model.OptionSpec o : parsed.matchedOptions()) {
            if (COVERAGE_OF_ONE_RUN.contains(o.longestName())) {
                throw usage(o.longestName() + " is an option of one run's coverage (dtron run); the runs against"
                        + " mutants end when a run FAILS or after --budget time units, and their coverage is not kept");
            }
            if (NOT_FOR_MUTANTS.contains(o.longestName())) {
                throw usage(o.longestName() + (o.longestName().equals("--timeout")
                        ? " is dtron run's: give each mutant's run its time units with --budget"
                        : " is an option of a run against one system under test; mutants are run in this process"
                        + " in virtual time"));
            }
        }
        if (parsed.isUsageHelpRequested() || parsed.isVersionHelpRequested()) {
            throw usage("--help and --version go before the model");
        }
        return run;
    }

    private static void printTable(MutationReport report, PrintWriter out) {
        List<String[]> rows = new ArrayList<>();
        rows.add(new String[] {"#", "kind", "change", "where", "result"});
        for (MutationReport.Outcome o : report.outcomes()) {
            Mutant m = o.mutant();
            rows.add(new String[] {String.valueOf(m.number()), m.kind().label(), m.change(), shortWhere(m.where()),
                    result(o)});
        }
        int[] widths = new int[5];
        for (String[] row : rows) {
            for (int i = 0; i < 4; i++) {
                widths[i] = Math.max(widths[i], row[i].length());
            }
        }
        for (String[] row : rows) {
            StringBuilder line = new StringBuilder();
            for (int i = 0; i < 4; i++) {
                String cell = row[i];
                line.append(i == 0 ? " ".repeat(widths[0] - cell.length()) + cell
                        : cell + " ".repeat(widths[i] - cell.length())).append("  ");
            }
            out.println(line.append(row[4]).toString().stripTrailing());
        }
    }

    private static String result(MutationReport.Outcome o) {
        return switch (o.status()) {
            case KILLED -> "killed (seed " + o.seed() + ")";
            case SURVIVED -> "survived";
            case EQUIVALENT -> "equivalent: " + o.explanation();
            case INVALID -> "invalid: " + o.explanation();
        };
    }

    /** {@code file:line} with the file's name alone. */
    private static String shortWhere(String where) {
        int colon = where.lastIndexOf(':');
        String file = colon < 0 ? where : where.substring(0, colon);
        Path name = Path.of(file).getFileName();
        return (name == null ? file : name.toString()) + (colon < 0 ? "" : where.substring(colon));
    }

    private static void printSummary(MutationReport r, int threads, PrintWriter out) {
        long killed = r.count(MutationReport.Status.KILLED);
        out.println("mutation score: " + killed + "/" + r.total() + (r.total() == 0 ? "" : String.format(Locale.ROOT,
                " (%.0f%%)", 100 * r.score())) + ": " + killed + " killed, " + r.count(MutationReport.Status.SURVIVED)
                + " survived; not counted: " + r.count(MutationReport.Status.EQUIVALENT) + " equivalent, "
                + r.count(MutationReport.Status.INVALID) + " invalid");
        if (r.modelRuns() == r.seeds().size()) {
            out.println("the model as its own system: PASSED with every seed (" + r.seeds().size() + ")");
        } else {
            out.println("the model as its own system: " + r.modelRuns() + " of " + r.seeds().size() + " runs PASSED;"
                    + " " + r.modelProblem());
        }
        double seconds = Math.max(r.wallNanos() / 1e9, 1e-9);
        out.println(String.format(Locale.ROOT, "%d mutants, %d runs of %d time units, in %.2f s on %d thread%s: %.1f"
                + " mutants/s, %.0f runs/s", r.outcomes().size(), r.runs(), r.budget(), seconds, threads,
                threads == 1 ? "" : "s", r.outcomes().size() / seconds, r.runs() / seconds));
    }

    /**
     * {@code --junit}: a test case per mutant, named by its number, kind, change and place (killed passes, survived is
     * a failure: no seed found it; equivalent and invalid are skipped, as they are not counted), and one for the model
     * as its own system (an error unless every seed PASSED); the seeds, the budget and the score as properties.
     */
    private void writeJunit(MutationReport r, TestOptions options, Steering steering, int threads)
            throws IOException {
        List<Long> seeds = r.seeds();
        String range = seeds.get(0) + (seeds.size() > 1 ? ".." + seeds.get(seeds.size() - 1) : "");
        List<JunitXml.Case> cases = new ArrayList<>();
        cases.add(r.modelRuns() == seeds.size() ? new JunitXml.Case("the model as its own system, seeds " + range,
                null, null, "PASSED with every seed") : new JunitXml.Case("the model as its own system, seeds " + range,
                "error", "INCONCLUSIVE", r.modelRuns() + " of " + seeds.size() + " runs PASSED; " + r.modelProblem()));
        for (MutationReport.Outcome o : r.outcomes()) {
            Mutant m = o.mutant();
            String name = "mutant " + m.number() + ": " + m.kind().label() + ", " + m.change() + " (" + shortWhere(
                    m.where()) + ")";
            cases.add(switch (o.status()) {
                case KILLED -> new JunitXml.Case(name, null, null, "killed by seed " + o.seed());
                case SURVIVED -> new JunitXml.Case(name, "failure", "SURVIVED", "survived seeds " + range + ": "
                        + o.explanation());
                case EQUIVALENT -> new JunitXml.Case(name, "skipped", "EQUIVALENT", "equivalent: " + o.explanation());
                case INVALID -> new JunitXml.Case(name, "skipped", "INVALID", "invalid: " + o.explanation());
            });
        }
        java.util.Map<String, String> properties = new java.util.LinkedHashMap<>();
        properties.put("model", model.toString());
        properties.put("seeds", range);
        properties.put("budget", Long.toString(r.budget()));
        properties.put("timeunit_us", Long.toString(options.timeUnitMicros()));
        properties.put("delay_policy", options.delayPolicy().name().toLowerCase(Locale.ROOT).replace('_', '-'));
        properties.put("strategy", steering == null ? "random" : steering.strategy().name().toLowerCase(Locale.ROOT));
        properties.put("mutation_score", r.count(MutationReport.Status.KILLED) + "/" + r.total());
        for (MutationReport.Status status : MutationReport.Status.values()) {
            properties.put(status.name().toLowerCase(Locale.ROOT), Long.toString(r.count(status)));
        }
        properties.put("model_runs_passed", r.modelRuns() + "/" + seeds.size());
        StringWriter summary = new StringWriter();
        printSummary(r, threads, new PrintWriter(summary));
        JunitXml.write(junit, "dtron mutants " + model, JunitXml.className("dtron.mutants.", model), cases,
                properties, r.wallNanos() / 1e9, summary.toString());
    }

    private String json(MutationReport r, TestOptions options, Steering steering) {
        StringBuilder sb = new StringBuilder("{");
        sb.append("\"model\":").append(JsonTrace.quote(model.toString()));
        sb.append(",\"seeds\":").append(r.seeds().stream().map(String::valueOf).collect(Collectors.joining(",", "[",
                "]")));
        sb.append(",\"budget\":").append(r.budget());
        sb.append(",\"timeunit_us\":").append(options.timeUnitMicros());
        sb.append(",\"delay_policy\":").append(JsonTrace.quote(options.delayPolicy().name()
                .toLowerCase(Locale.ROOT).replace('_', '-')));
        sb.append(",\"strategy\":").append(JsonTrace.quote(steering == null ? "random"
                : steering.strategy().name().toLowerCase(Locale.ROOT)));
        for (MutationReport.Status s : MutationReport.Status.values()) {
            sb.append(",\"").append(s.name().toLowerCase(Locale.ROOT)).append("\":").append(r.count(s));
        }
        sb.append(",\"score\":").append(String.format(Locale.ROOT, "%.4f", r.score()));
        sb.append(",\"model_runs_passed\":").append(r.modelRuns());
        sb.append(",\"runs\":").append(r.runs());
        sb.append(",\"wall_s\":").append(String.format(Locale.ROOT, "%.3f", r.wallNanos() / 1e9));
        sb.append(",\"mutants\":[");
        boolean first = true;
        for (MutationReport.Outcome o : r.outcomes()) {
            Mutant m = o.mutant();
            sb.append(first ? "" : ",").append("\n{\"number\":").append(m.number())
                    .append(",\"kind\":").append(JsonTrace.quote(m.kind().label()))
                    .append(",\"process\":").append(JsonTrace.quote(m.process()))
                    .append(",\"change\":").append(JsonTrace.quote(m.change()))
                    .append(",\"where\":").append(JsonTrace.quote(m.where()))
                    .append(",\"status\":").append(JsonTrace.quote(o.status().name().toLowerCase(Locale.ROOT)))
                    .append(o.status() == MutationReport.Status.KILLED ? ",\"seed\":" + o.seed() : "")
                    .append(",\"explanation\":").append(JsonTrace.quote(o.explanation())).append('}');
            first = false;
        }
        return sb.append("]}\n").toString();
    }

    private ParameterException usage(String message) {
        return new ParameterException(spec.commandLine(), "dtron mutants: " + message);
    }
}
