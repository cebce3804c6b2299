package io.dtron.cli;

import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.model.TestInterface.ObservableChannel;
import io.dtron.model.delta.DeltaExtension;
import io.dtron.model.delta.DeltaExtension.Change;
import io.dtron.model.delta.DeltaExtension.Delay;
import io.dtron.model.delta.DeltaExtension.Left;
import io.dtron.model.delta.DeltaExtension.Result;
import io.dtron.xta.ModelSyntax;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.file.AtomicMoveNotSupportedException;
import java.nio.file.FileAlreadyExistsException;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.Callable;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import java.util.stream.Collectors;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron delta MODEL (--delta CHANNEL=LOW..HIGH ... | --delta-from REPORT.json) -o OUT}: writes the
 * Delta-extended model (thesis section 3.5, step 2), the model with the clock bounds of its observable edges widened
 * by the delays between tester and system, for re-verification. See {@link DeltaExtension}.
 */
@Command(name = "delta", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Write the Delta-extended model: the clock bounds of the edges on inputs and outputs widened by"
                + " the delays between tester and system (thesis 3.5, step 2), to verify the model again with them.",
                "Lower bounds of guards grow by low_in + low_out (rounded down to time units), upper bounds of guards"
                        + " and of source invariants by high_in + high_out (rounded up); the rest of the file is kept"
                        + " byte for byte, with a comment at the top of the global declarations saying what was"
                        + " widened.",
                "Exit code 0 when the model is written, 1 otherwise."})
final class DeltaCommand implements Callable<Integer> {
    private static final Pattern INTERVAL = Pattern.compile("([^=\\s]+)=(\\d{1,18})\\.\\.(\\d{1,18})");

    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The model (.xml or .xta).")
    private Path model;

    @Option(names = "--interface", paramLabel = "FILE.trn",
            description = "TRON interface file (inputs, outputs, precision); by default i_/o_ channel names give the"
                    + " interface.")
    private Path interfaceFile;

    @Option(names = "--delta", paramLabel = "CHANNEL=LOW..HIGH",
            description = "The delays of a channel in microseconds, e.g. move=200..1500 (the bus name, without i_/o_;"
                    + " its direction comes from the interface). Repeat for more channels.")
    private List<String> delta = List.of();

    @Option(names = "--delta-from", paramLabel = "REPORT.json",
            description = "The delays measured by a run: the report of dtron run --delta-report.")
    private Path report;

    @Option(names = "--timeunit", paramLabel = "US",
            description = "Microseconds per model time unit (default: the report's, else the interface file's"
                    + " precision, else 1000).")
    private Long timeUnit;

    @Option(names = {"-o", "--output"}, paramLabel = "OUT", required = true,
            description = "Where to write the Delta-extended model, in the model's own format.")
    private Path output;

    @Option(names = "--force", description = "Overwrite OUT when it exists.")
    private boolean force;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        try {
            return extend(out, err);
        } catch (Refusal r) {
            err.println("dtron delta: " + r.getMessage());
            return 1;
        } finally {
            out.flush();
            err.flush();
        }
    }

    /** A reason to stop, said on one line. */
    private static final class Refusal extends Exception {
        Refusal(String message) {
            super(message, null, false, false);
        }
    }

    private int extend(PrintWriter out, PrintWriter err) throws Refusal {
        if (delta.isEmpty() == (report == null)) {
            throw new Refusal(report == null ? "give the delays: --delta CHANNEL=LOW..HIGH ... or --delta-from"
                    + " REPORT.json" : "give the delays either with --delta or with --delta-from, not both");
        }
        if (timeUnit != null && timeUnit <= 0) {
            throw new Refusal("--timeunit must be a positive number of microseconds, not " + timeUnit);
        }
        if (Files.exists(output) && !force) {
            throw new Refusal(output + " exists; give --force to overwrite it");
        }
        Map<String, Delay> delays = report == null ? parseDeltas() : null;
        DeltaReport measured = report == null ? null : readReport();
        byte[] bytes = readModel();
        String text = ModelSyntax.decode(bytes);
        checkFormat(ModelSyntax.isXml(text));
        Network network;
        TestInterface testInterface;
        try {
            network = ModelLoader.load(model.toString(), text);
        } catch (ModelException e) {
            CheckCommand.printErrors(model, e, err);
            return 1;
        } catch (OutOfMemoryError e) {
            throw new Refusal(JvmLimits.modelTooLarge("delta", model));
        }
        try {
            testInterface = interfaceFile == null ? TestInterface.fromNames(network)
                    : TestInterface.fromFile(network, interfaceFile);
        } catch (ModelException e) {
            CheckCommand.printErrors(interfaceFile == null ? model : interfaceFile, e, err);
            return 1;
        }
        if (measured != null) {
            delays = fromReport(measured, testInterface, err);
        } else {
            for (String d : delta) {
                direction(testInterface, d.substring(0, d.indexOf('=')).trim(), "--delta " + d);
            }
        }
        long unit = RunDefaults.timeUnit(timeUnit, measured == null ? null : measured.timeUnitMicros(),
                testInterface.timeUnitMicros());
        String source = report == null ? "--delta " + String.join(" --delta ", delta)
                : "the delays of " + report.getFileName() + (measured.runId() == null ? "" : " (run " + measured.runId()
                + ")");
        Result result;
        try {
            result = DeltaExtension.extend(network, text, testInterface, delays, unit, source);
        } catch (IllegalArgumentException e) {
            throw new Refusal(e.getMessage());
        }
        write(DeltaExtension.encodeLike(result.text(), bytes));
        summary(out, err, result, testInterface, delays, unit);
        return 0;
    }

    private Map<String, Delay> parseDeltas() throws Refusal {
        Map<String, Delay> delays = new LinkedHashMap<>();
        for (String d : delta) {
            Matcher m = INTERVAL.matcher(d.trim());
            if (!m.matches()) {
                throw new Refusal("--delta " + d + ": expected CHANNEL=LOW..HIGH, LOW and HIGH whole numbers of"
                        + " microseconds, at least 0, e.g. move=200..1500");
            }
            long low = Long.parseLong(m.group(2));
            long high = Long.parseLong(m.group(3));
            if (low > high) {
                throw new Refusal("--delta " + d + ": LOW is above HIGH");
            }
            if (delays.put(m.group(1), new Delay(low, high)) != null) {
                throw new Refusal("--delta " + d + ": channel " + m.group(1) + " is given twice");
            }
        }
        return delays;
    }

    /** Refuses an output name whose extension says the other format: the model is written in its own. */
    private void checkFormat(boolean xml) throws Refusal {
        String name = output.getFileName() == null ? "" : output.getFileName().toString().toLowerCase(Locale.ROOT);
        boolean text = name.endsWith(".xta") || name.endsWith(".ta");
        if (xml ? text : name.endsWith(".xml")) {
            throw new Refusal(output + ": the Delta-extended model is written in the model's own format, "
                    + (xml ? "Uppaal XML; name it .xml" : "text; name it .xta"));
        }
    }

    private DeltaReport readReport() throws Refusal {
        String json;
        try {
            json = Files.readString(report);
        } catch (NoSuchFileException e) {
            throw new Refusal(report + ": no such file");
        } catch (IOException e) {
            throw new Refusal(report + ": cannot read the report: " + e.getMessage());
        }
        try {
            return DeltaReport.parse(json);
        } catch (IllegalArgumentException e) {
            throw new Refusal(report + " is not a delay report of dtron run --delta-report: " + e.getMessage());
        }
    }

    private byte[] readModel() throws Refusal {
        try {
            return Files.readAllBytes(model);
        } catch (NoSuchFileException e) {
            throw new Refusal(model + ": no such file");
        } catch (IOException e) {
            throw new Refusal(model + ": cannot read the model: " + e.getMessage());
        }
    }

    /** Whether {@code channel} is an input of the interface (else an output); a refusal when it is neither. */
    private boolean direction(TestInterface testInterface, String channel, String where) throws Refusal {
        if (testInterface.input(channel).isPresent()) {
            return true;
        }
        if (testInterface.output(channel).isPresent()) {
            return false;
        }
        String bare = channel.length() > 2 && (channel.startsWith("i_") || channel.startsWith("o_"))
                ? channel.substring(2) : null;
        boolean known = bare != null
                && (testInterface.input(bare).isPresent() || testInterface.output(bare).isPresent());
        throw new Refusal(where + ": unknown channel '" + channel + "'" + (known ? " (name it '" + bare + "', its name"
                + " on the bus, without i_/o_)" : "") + ": the model's inputs are " + names(testInterface.inputs())
                + ", its outputs " + names(testInterface.outputs()));
    }

    private static String names(List<ObservableChannel> channels) {
        return channels.isEmpty() ? "none" : channels.stream().map(ObservableChannel::name)
                .collect(Collectors.joining(", "));
    }

    private Map<String, Delay> fromReport(DeltaReport measured, TestInterface testInterface, PrintWriter err)
            throws Refusal {
        String measuredName = measured.model() == null ? null
                : measured.model().substring(Math.max(measured.model().lastIndexOf('/'),
                measured.model().lastIndexOf('\\')) + 1);
        if (measuredName != null && !measuredName.equals(String.valueOf(model.getFileName()))) {
            err.println("dtron delta: warning: " + report + " was measured with model " + measured.model() + ", not "
                    + model.getFileName());
        }
        for (DeltaReport.Channel c : measured.channels()) {
            boolean input = direction(testInterface, c.channel(), report.toString());
            if (input != c.input()) {
                throw new Refusal(report + ": channel '" + c.channel() + "' is an " + (c.input() ? "input" : "output")
                        + " in the report but an " + (input ? "input" : "output") + " of " + model);
            }
        }
        Map<String, Delay> delays = measured.measured();
        if (delays.isEmpty()) {
            throw new Refusal(report + " measured no channel (every count is 0): nothing to widen");
        }
        return delays;
    }

    /** Writes OUT through a temporary file next to it, so that a failed write leaves no half-written model. */
    private void write(byte[] bytes) throws Refusal {
        Path target = output.toAbsolutePath();
        try {
            if (Files.exists(target) && Files.isSameFile(target, model)) {
                throw new Refusal(output + " is the model itself; write the Delta-extended model to another file");
            }
            Path tmp = Files.createTempFile(target.getParent(), ".dtron-delta-", ".tmp");
            try {
                Files.write(tmp, bytes);
                move(tmp, target);
            } finally {
                Files.deleteIfExists(tmp);
            }
        } catch (FileAlreadyExistsException e) {
            throw new Refusal(output + " exists; give --force to overwrite it");
        } catch (NoSuchFileException e) {
            throw new Refusal("cannot write " + output + ": no such folder " + target.getParent());
        } catch (IOException e) {
            throw new Refusal("cannot write " + output + ": " + e.getMessage());
        }
    }

    private void move(Path tmp, Path target) throws IOException {
        if (!force) {
            Files.move(tmp, target);
            return;
        }
        try {
            Files.move(tmp, target, StandardCopyOption.REPLACE_EXISTING, StandardCopyOption.ATOMIC_MOVE);
        } catch (AtomicMoveNotSupportedException e) {
            Files.move(tmp, target, StandardCopyOption.REPLACE_EXISTING);
        }
    }

    private void summary(PrintWriter out, PrintWriter err, Result result, TestInterface testInterface,
                         Map<String, Delay> delays, long unit) {
        out.println("dtron delta: " + model + " -> " + output + ", time unit " + unit + " us");
        for (Map.Entry<String, Delay> d : delays.entrySet()) {
            String direction = testInterface.input(d.getKey()).isPresent() ? "input " : "output";
            out.printf("  %s %s %d..%d us (%d..%d units)%n", direction, d.getKey(), d.getValue().lowMicros(),
                    d.getValue().highMicros(), Math.floorDiv(d.getValue().lowMicros(), unit),
                    -Math.floorDiv(-d.getValue().highMicros(), unit));
        }
        out.println("widened " + result.changes().size() + (result.changes().size() == 1 ? " bound" : " bounds")
                + (result.changes().isEmpty() ? "" : ":"));
        for (Change c : result.changes()) {
            out.println("  " + c.place() + ": " + c.before() + "  ->  " + c.after());
        }
        if (!result.left().isEmpty()) {
            out.println("left " + result.left().size() + " clock comparison" + (result.left().size() == 1 ? "" : "s")
                    + " as written:");
            for (Left l : result.left()) {
                out.println("  " + l.place() + ": " + l.text() + ": " + l.reason());
            }
        }
        for (String w : result.warnings()) {
            err.println("dtron delta: warning: " + w);
        }
    }
}
