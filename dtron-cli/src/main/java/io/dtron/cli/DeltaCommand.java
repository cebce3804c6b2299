package io.dtron.cli;

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
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
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
    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The model (.xml or .xta).")
    private Path model;

    @Mixin
    private DeltaDelays delays;

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
        } catch (DeltaDelays.Refusal r) {
            err.println("dtron delta: " + r.getMessage());
            return 1;
        } finally {
            out.flush();
            err.flush();
        }
    }

    private int extend(PrintWriter out, PrintWriter err) throws DeltaDelays.Refusal {
        if (Files.exists(output) && !force) {
            throw new DeltaDelays.Refusal(output + " exists; give --force to overwrite it");
        }
        DeltaDelays.Extended extended = delays.extend("delta", model, err);
        if (extended == null) {
            return 1;
        }
        checkFormat(ModelSyntax.isXml(extended.result().text()));
        write(DeltaExtension.encodeLike(extended.result().text(), extended.bytes()));
        summary(out, extended);
        return 0;
    }

    /** Refuses an output name whose extension says the other format: the model is written in its own. */
    private void checkFormat(boolean xml) throws DeltaDelays.Refusal {
        String name = output.getFileName() == null ? "" : output.getFileName().toString().toLowerCase(Locale.ROOT);
        boolean text = name.endsWith(".xta") || name.endsWith(".ta");
        if (xml ? text : name.endsWith(".xml")) {
            throw new DeltaDelays.Refusal(output + ": the Delta-extended model is written in the model's own format, "
                    + (xml ? "Uppaal XML; name it .xml" : "text; name it .xta"));
        }
    }

    /** Writes OUT through a temporary file next to it, so that a failed write leaves no half-written model. */
    private void write(byte[] bytes) throws DeltaDelays.Refusal {
        Path target = output.toAbsolutePath();
        try {
            if (Files.exists(target) && Files.isSameFile(target, model)) {
                throw new DeltaDelays.Refusal(output + " is the model itself; write the Delta-extended model to another"
                        + " file");
            }
            Path tmp = Files.createTempFile(target.getParent(), ".dtron-delta-", ".tmp");
            try {
                Files.write(tmp, bytes);
                move(tmp, target);
            } finally {
                Files.deleteIfExists(tmp);
            }
        } catch (FileAlreadyExistsException e) {
            throw new DeltaDelays.Refusal(output + " exists; give --force to overwrite it");
        } catch (NoSuchFileException e) {
            throw new DeltaDelays.Refusal("cannot write " + output + ": no such folder " + target.getParent());
        } catch (IOException e) {
            throw new DeltaDelays.Refusal("cannot write " + output + ": " + OutputFile.reason(e));
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

    private void summary(PrintWriter out, DeltaDelays.Extended extended) {
        long unit = extended.unitMicros();
        Result result = extended.result();
        out.println("dtron delta: " + model + " -> " + output + ", time unit " + unit + " us");
        for (Map.Entry<String, Delay> d : extended.delays().entrySet()) {
            String direction = extended.testInterface().input(d.getKey()).isPresent() ? "input " : "output";
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
    }
}
