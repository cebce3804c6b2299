package io.dtron.tron;

import io.dtron.cli.DtronCommand;
import io.dtron.model.ModelLoader;
import java.nio.file.Path;
import java.util.Arrays;
import java.io.PrintWriter;

/**
 * A stand-in for an installed TRON in tests of the TRON backend: DTRON's own {@code dtron tron} with TRON's command
 * line, in a JVM of its own, launched by a shell script called {@code tron}. On LightContr it warms up first, so that
 * a cold JVM does not make its first real-time inputs late.
 */
public final class FakeTronMain {
    private FakeTronMain() {
    }

    public static void main(String[] args) throws Exception {
        int separator = Arrays.asList(args).indexOf("--");
        Path model = Path.of(args[separator - 1]);
        if (model.getFileName().toString().equals("LightContr.xml")) {
            Warmup.lightContr(ModelLoader.load(model));
        }
        String[] withCommand = new String[args.length + 1];
        withCommand[0] = "tron";
        System.arraycopy(args, 0, withCommand, 1, args.length);
        System.exit(DtronCommand.run(withCommand, new PrintWriter(System.out, true), new PrintWriter(System.err, true)));
    }
}
