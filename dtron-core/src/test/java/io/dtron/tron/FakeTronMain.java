package io.dtron.tron;

import io.dtron.cli.TronCommand;
import io.dtron.model.ModelLoader;
import java.nio.file.Path;
import java.util.Arrays;
import picocli.CommandLine;

/**
 * A stand-in for an installed TRON in tests of the TRON backend: DTRON's own {@code dtron tron} with TRON's command
 * line, in a JVM of its own, launched by a shell script called {@code tron}. It warms up on the model first, so that
 * a cold JVM does not make its first real-time inputs late.
 */
public final class FakeTronMain {
    private FakeTronMain() {
    }

    public static void main(String[] args) throws Exception {
        int separator = Arrays.asList(args).indexOf("--");
        Warmup.lightContr(ModelLoader.load(Path.of(args[separator - 1])));
        System.exit(new CommandLine(new TronCommand()).execute(args));
    }
}
