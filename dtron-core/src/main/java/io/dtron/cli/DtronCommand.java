package io.dtron.cli;

import java.io.PrintWriter;
import java.util.concurrent.Callable;
import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Spec;

/**
 * The {@code dtron} command line: {@code dtron check MODEL...} loads and type-checks models, {@code dtron run
 * MODEL --sut CLASS} tests a system under test against a model. Exit codes follow TRON's: 0 passed, 2 failed,
 * 3 inconclusive; 1 for a usage or model error.
 */
@Command(name = "dtron", mixinStandardHelpOptions = true, versionProvider = DtronCommand.Version.class,
        exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = "Online model-based testing and control of timed systems with Uppaal timed automata.",
        subcommands = {CheckCommand.class, RunCommand.class, CommandLine.HelpCommand.class})
public final class DtronCommand implements Callable<Integer> {

    @Spec
    private CommandSpec spec;

    /** Runs the command line and exits with its exit code. */
    public static void main(String[] args) {
        System.exit(run(args, new PrintWriter(System.out, true), new PrintWriter(System.err, true)));
    }

    /** Runs the command line with the given output streams and returns the exit code. */
    public static int run(String[] args, PrintWriter out, PrintWriter err) {
        CommandLine cli = new CommandLine(new DtronCommand());
        cli.setOut(out);
        cli.setErr(err);
        cli.setExecutionExceptionHandler((e, commandLine, parseResult) -> {
            commandLine.getErr().println("dtron: internal error: " + e);
            e.printStackTrace(commandLine.getErr());
            return 1;
        });
        return cli.execute(args);
    }

    @Override
    public Integer call() {
        spec.commandLine().usage(spec.commandLine().getErr());
        return 1;
    }

    /** The version from the jar's manifest. */
    static final class Version implements CommandLine.IVersionProvider {
        @Override
        public String[] getVersion() {
            String v = DtronCommand.class.getPackage().getImplementationVersion();
            return new String[] {"dtron " + (v == null ? "(development build)" : v),
                    "Java " + System.getProperty("java.version") + " on " + System.getProperty("os.name")};
        }
    }
}
