package io.dtron.cli;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.verify.TestabilityReport;
import io.dtron.engine.verify.VerificationResult;
import io.dtron.engine.verify.Verifier;
import io.dtron.engine.verify.VerifierOptions;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import io.dtron.xta.Diagnostic;
import io.dtron.xta.ast.Query;
import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.Callable;
import java.util.stream.Collectors;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron check MODEL...}: loads and type-checks models and prints a summary of each, or its errors; with
 * {@code --testability}, also whether each can serve as a test specification.
 */
@Command(name = "check", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Load and type-check Uppaal models (.xml, .xta, .ta).",
                "Prints a summary of each model (templates, processes, clocks, channels, inputs and outputs with"
                        + " their attached variables), or every error with its file, line and column.",
                "Exit code 0 when every model loads (and, with --testability, passes), 2 when a testability check"
                        + " fails, 1 for an error."})
final class CheckCommand implements Callable<Integer> {
    private static final int MAX_NAMES = 8;

    @Spec
    private CommandSpec spec;

    @Parameters(arity = "1..*", paramLabel = "MODEL", description = "Model files to check.")
    private List<Path> models;

    @Option(names = "--interface", paramLabel = "FILE.trn",
            description = "TRON interface file (inputs, outputs, attached variables) for the model (one model"
                    + " only); by default the interface comes from i_/o_ channel names.")
    private Path interfaceFile;

    @Option(names = {"-q", "--quiet"}, description = "Print errors only.")
    private boolean quiet;

    @Option(names = "--testability", description = "Also check that the model can serve as a test specification:"
            + " output observability, input enabledness, connectedness and strong responsiveness (with a generated"
            + " canonical tester), coverage by the model's environment, time-lock and Zeno freedom (exit code 2 when"
            + " a check fails).")
    private boolean testability;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (interfaceFile != null && models.size() != 1) {
            err.println("dtron check: --interface applies to one model, but " + models.size() + " were given");
            return 1;
        }
        int failed = 0;
        int untestable = 0;
        for (Path model : models) {
            try {
                Network network = ModelLoader.load(model);
                TestInterface testInterface = interfaceFile == null ? TestInterface.fromNames(network)
                        : TestInterface.fromFile(network, interfaceFile);
                if (!quiet) {
                    summary(out, network, testInterface);
                }
                for (Query q : network.queries()) {
                    for (Diagnostic d : q.errors()) {
                        out.println("  " + d.format());
                    }
                }
                if (testability && !testability(out, network, testInterface)) {
                    untestable++;
                }
            } catch (UnsupportedModelException e) {
                failed++;
                err.println("dtron check: " + model + ": " + e.getMessage());
            } catch (ModelException e) {
                failed++;
                printErrors(model, e, err);
            } catch (OutOfMemoryError e) {
                failed++;
                err.println("dtron check: " + JvmLimits.modelTooLarge("check", model));
            }
        }
        out.flush();
        err.flush();
        return failed > 0 ? 1 : untestable > 0 ? 2 : 0;
    }

    /** Runs the testability checks and prints each with its problems; true when all pass. */
    private static boolean testability(PrintWriter out, Network network, TestInterface testInterface) {
        TestabilityReport report = new Verifier(network, VerifierOptions.defaults()).testability(testInterface);
        VerificationResult.Statistics s = report.statistics();
        out.printf("  testability (%,d states explored, %.2f s):%n", s.explored(), s.time().toNanos() / 1e9);
        for (TestabilityReport.Check c : report.checks()) {
            out.printf("    %-22s %s%n", c.name(), c.passed() ? "ok" : c.problems().size() + " problem"
                    + (c.problems().size() == 1 ? "" : "s"));
            if (c.note() != null && (!c.passed() || c.note().startsWith("not checked")
                    || c.note().startsWith("unknown") || c.note().startsWith("partly"))) {
                out.println("      (" + c.note() + ")");
            }
            for (TestabilityReport.Problem p : c.problems()) {
                out.println("      - " + p.message());
                if (p.trace() != null) {
                    out.print(p.trace().toText().replaceAll("(?m)^", "      "));
                }
            }
        }
        return report.passed();
    }

    /** Prints a model's errors: the count, then each with its place. The other commands print them the same way. */
    static void printErrors(Path model, ModelException e, PrintWriter err) {
        err.println(model + ": " + e.errors().size() + " error" + (e.errors().size() == 1 ? "" : "s"));
        for (Diagnostic d : e.diagnostics()) {
            err.println("  " + d.format());
        }
    }

    private static void summary(PrintWriter out, Network n, TestInterface i) {
        out.println(n.file() + ": ok");
        List<String> templates = n.templates();
        row(out, "templates", templates.size(), names(templates));
        row(out, "processes", n.processes().size(), names(n.processes().stream().map(Process::name).toList()));
        row(out, "clocks", n.clockCount(), names(n.clocks().stream().map(c -> c.name()
                + (c.type().clocks() > 1 ? "[" + c.type().clocks() + "]" : "")).toList()));
        long urgent = n.channels().stream().filter(c -> c.kind().urgent()).mapToLong(c -> c.type().channels()).sum();
        long broadcast = n.channels().stream().filter(c -> c.kind().broadcast())
                .mapToLong(c -> c.type().channels()).sum();
        row(out, "channels", n.channelCount(), n.channelCount() == 0 ? ""
                : "(" + urgent + " urgent, " + broadcast + " broadcast) " + names(n.channels().stream()
                .map(c -> c.name() + (c.type().channels() > 1 ? "[" + c.type().channels() + "]" : "")).toList()));
        row(out, "variables", n.variables().size(), "(" + n.stateSize() + " integer slots)");
        row(out, "inputs", i.inputs().size(), channels(i.inputs()));
        row(out, "outputs", i.outputs().size(), channels(i.outputs()));
        if (i.timeUnitMicros() != null || i.timeout() != null) {
            out.printf("  %-10s %s%n", "timing", (i.timeUnitMicros() == null ? "" : "time unit " + i.timeUnitMicros()
                    + " us ") + (i.timeout() == null ? "" : "timeout " + i.timeout() + " units"));
        }
        if (i.inputs().isEmpty() && i.outputs().isEmpty()) {
            out.printf("  %-10s %s%n", "", "(name channels i_x / o_y, or give --interface FILE.trn, to test the model)");
        }
        long invalid = n.queries().stream().filter(q -> !q.isValid()).count();
        if (!n.queries().isEmpty()) {
            row(out, "queries", n.queries().size(), invalid == 0 ? "" : "(" + invalid + " with errors; they do not"
                    + " stop the model from loading or running)");
        }
        for (Diagnostic w : n.warnings()) {
            out.println("  " + w.format());
        }
    }

    private static void row(PrintWriter out, String what, long count, String details) {
        out.printf("  %-10s %4d  %s%n", what, count, details);
    }

    private static String names(List<String> names) {
        if (names.size() <= MAX_NAMES) {
            return String.join(", ", names);
        }
        return String.join(", ", names.subList(0, MAX_NAMES)) + " and " + (names.size() - MAX_NAMES) + " more";
    }

    /** The channels with their attached variables, as {@code name(var, ...)}, comma-separated. */
    static String channels(List<TestInterface.ObservableChannel> channels) {
        return channels.stream().map(c -> c.name() + "(" + c.variables().stream()
                .map(TestInterface.AttachedVariable::name).collect(Collectors.joining(", ")) + ")")
                .collect(Collectors.joining(", "));
    }
}
