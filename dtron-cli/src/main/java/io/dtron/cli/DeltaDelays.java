package io.dtron.cli;

import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.model.TestInterface.ObservableChannel;
import io.dtron.model.delta.DeltaExtension;
import io.dtron.model.delta.DeltaExtension.Delay;
import io.dtron.model.delta.DeltaExtension.Result;
import io.dtron.xta.ModelSyntax;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import java.util.stream.Collectors;
import picocli.CommandLine.Option;

/**
 * The delays between tester and system, given by hand ({@code --delta CHANNEL=LOW..HIGH}) or measured by a run
 * ({@code --delta-from REPORT.json}), and the Delta-extended model they make (thesis 3.5, step 2): mixed into {@code
 * dtron delta}, which writes that model, and {@code dtron verify}, which checks it (step 3).
 */
final class DeltaDelays {
    private static final Pattern INTERVAL = Pattern.compile("([^=\\s]+)=(\\d{1,18})\\.\\.(\\d{1,18})");

    @Option(names = "--interface", paramLabel = "FILE.trn",
            description = "TRON interface file (inputs, outputs, precision) of the delays' channels; by default i_/o_"
                    + " channel names give the interface.")
    private Path interfaceFile;

    @Option(names = "--delta", paramLabel = "CHANNEL=LOW..HIGH",
            description = "The delays of a channel in microseconds, e.g. move=200..1500 (the bus name, without i_/o_;"
                    + " its direction comes from the interface). Repeat for more channels.")
    private List<String> delta = List.of();

    @Option(names = "--delta-from", paramLabel = "REPORT.json",
            description = "The delays measured by a run: the report of dtron run --delta-report.")
    private Path report;

    @Option(names = "--timeunit", paramLabel = "US",
            description = "With the delays: microseconds per model time unit (default: the report's, else the"
                    + " interface file's precision, else 1000).")
    private Long timeUnit;

    /** A reason to stop, said on one line. */
    static final class Refusal extends Exception {
        Refusal(String message) {
            super(message, null, false, false);
        }
    }

    /**
     * A Delta-extended model.
     *
     * @param original      the model as written
     * @param bytes         the model file's bytes, as written
     * @param testInterface its test interface
     * @param delays        the delays of its channels, by bus name
     * @param unitMicros    the time unit the delays were rounded to
     * @param source        where the delays came from, for messages
     * @param result        the widened text with what changed
     */
    record Extended(Network original, byte[] bytes, TestInterface testInterface, Map<String, Delay> delays,
                    long unitMicros, String source, Result result) {
        /** The Delta-extended model, loaded. */
        Network load(Path model) throws ModelException {
            return ModelLoader.load(model.toString(), result.text());
        }
    }

    /** Whether delays were given ({@code --delta} or {@code --delta-from}). */
    boolean given() {
        return !delta.isEmpty() || report != null;
    }

    /** Whether an option that only goes with the delays was given without them. */
    boolean strayOptions() {
        return !given() && (interfaceFile != null || timeUnit != null);
    }

    /**
     * Reads and loads {@code model} and widens it by the delays; model errors are printed (then null is returned),
     * warnings too, prefixed by {@code command}.
     */
    Extended extend(String command, Path model, PrintWriter err) throws Refusal {
        if (delta.isEmpty() == (report == null)) {
            throw new Refusal(report == null ? "give the delays: --delta CHANNEL=LOW..HIGH ... or --delta-from"
                    + " REPORT.json" : "give the delays either with --delta or with --delta-from, not both");
        }
        if (timeUnit != null && timeUnit <= 0) {
            throw new Refusal("--timeunit must be a positive number of microseconds, not " + timeUnit);
        }
        Map<String, Delay> delays = report == null ? parseDeltas() : null;
        DeltaReport measured = report == null ? null : readReport();
        byte[] bytes = readModel(model);
        String text = ModelSyntax.decode(bytes);
        Network network;
        TestInterface testInterface;
        try {
            network = ModelLoader.load(model.toString(), text);
        } catch (ModelException e) {
            CheckCommand.printErrors(model, e, err);
            return null;
        } catch (OutOfMemoryError e) {
            throw new Refusal(JvmLimits.modelTooLarge(command, model));
        }
        try {
            testInterface = CommandModel.interfaceOf(network, interfaceFile);
        } catch (ModelException e) {
            CheckCommand.printErrors(interfaceFile == null ? model : interfaceFile, e, err);
            return null;
        }
        if (measured != null) {
            delays = fromReport(command, model, measured, testInterface, err);
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
        try {
            Result result = DeltaExtension.extend(network, text, testInterface, delays, unit, source);
            for (String w : result.warnings()) {
                err.println("dtron " + command + ": warning: " + w);
            }
            return new Extended(network, bytes, testInterface, delays, unit, source, result);
        } catch (IllegalArgumentException e) {
            throw new Refusal(e.getMessage());
        }
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

    private DeltaReport readReport() throws Refusal {
        String json;
        try {
            json = Files.readString(report);
        } catch (NoSuchFileException e) {
            throw new Refusal(report + ": no such file");
        } catch (IOException e) {
            throw new Refusal(report + ": cannot read the report: " + OutputFile.reason(e));
        }
        try {
            return DeltaReport.parse(json);
        } catch (IllegalArgumentException e) {
            throw new Refusal(report + " is not a delay report of dtron run --delta-report: " + e.getMessage());
        }
    }

    private static byte[] readModel(Path model) throws Refusal {
        try {
            return Files.readAllBytes(model);
        } catch (NoSuchFileException e) {
            throw new Refusal(model + ": no such file");
        } catch (IOException e) {
            throw new Refusal(model + ": cannot read the model: " + OutputFile.reason(e));
        }
    }

    /** Whether {@code channel} is an input of the interface (else an output); a refusal when it is neither. */
    private static boolean direction(TestInterface testInterface, String channel, String where) throws Refusal {
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

    private Map<String, Delay> fromReport(String command, Path model, DeltaReport measured,
            TestInterface testInterface, PrintWriter err) throws Refusal {
        String measuredName = measured.model() == null ? null
                : measured.model().substring(Math.max(measured.model().lastIndexOf('/'),
                measured.model().lastIndexOf('\\')) + 1);
        if (measuredName != null && !measuredName.equals(String.valueOf(model.getFileName()))) {
            err.println("dtron " + command + ": warning: " + report + " was measured with model " + measured.model()
                    + ", not " + model.getFileName());
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
}
