package io.dtron.cli;

import java.io.File;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.InvalidPathException;
import java.nio.file.Path;
import java.util.concurrent.Callable;
import org.slf4j.LoggerFactory;
import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;
import picocli.CommandLine.UnmatchedArgumentException;

/**
 * The {@code dtron} command line: {@code dtron check MODEL...} loads and type-checks models, {@code dtron verify
 * MODEL} checks queries on a model, {@code dtron run
 * MODEL} tests a system under test against a model, in process ({@code --sut CLASS}), through a TRON adapter
 * ({@code --tron-adapter}) or on the bus; {@code dtron tron} takes Uppaal TRON's command line; {@code dtron
 * MODEL ...} is short for {@code dtron run MODEL ...}; {@code dtron delta} writes the Delta-extended model;
 * {@code dtron mutants MODEL} runs the tester against mutants of the model's implementation part; {@code dtron
 * report TRACE -o FILE.html} makes the HTML report of a recorded run. Exit
 * codes follow TRON's: 0 passed, 2 failed, 3 inconclusive; 1 for a usage or model error.
 */
@Command(name = "dtron", mixinStandardHelpOptions = true, versionProvider = DtronCommand.Version.class,
        exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Online model-based testing and control of timed systems with Uppaal timed automata.",
                "dtron MODEL [OPTIONS] is short for dtron run MODEL [OPTIONS]."},
        subcommands = {CheckCommand.class, RunCommand.class, TronCommand.class, VerifyCommand.class, DeltaCommand.class,
                CoverageCommand.class, MutantsCommand.class, ControlCommand.class, ReloadCommand.class,
                MonitorCommand.class,
                ReportCommand.class,
                CommandLine.HelpCommand.class})
public final class DtronCommand implements Callable<Integer> {
    @Spec
    private CommandSpec spec;

    /**
     * Runs the command line and exits with its exit code. Running out of heap or stack in any thread ends the
     * JVM with one line and exit code 1, not with a stack trace. A real-time run in this JVM compiles with C1 alone
     * ({@link RealTimeJit}).
     */
    public static void main(String[] args) {
        Thread.UncaughtExceptionHandler others = Thread.getDefaultUncaughtExceptionHandler();
        // a heap too small even for the line below (java -Xmx4m) gets this one, made while there was room
        byte[] lastResort = ("dtron: out of memory: the Java heap limit of " + (Runtime.getRuntime().maxMemory() >> 20)
                + " MB is too small for DTRON; raise it, e.g. java -Xmx256m -jar dtron.jar ...\n")
                .getBytes(StandardCharsets.UTF_8);
        try {
            // halting loads this class, which a full heap has no room for
            Class.forName("java.lang.Shutdown");
        } catch (ClassNotFoundException e) {
            // another JVM: the last resort line may be followed by the JVM's own
        }
        Thread.setDefaultUncaughtExceptionHandler((thread, e) -> {
            try {
                String limit = JvmLimits.describe(e);
                if (limit == null) {
                    if (others != null) {
                        others.uncaughtException(thread, e);
                    } else {
                        thread.getThreadGroup().uncaughtException(thread, e);
                    }
                    return;
                }
                System.err.println("dtron: " + limit + " (in thread " + thread.getName() + ")");
            } catch (OutOfMemoryError again) {
                try {
                    System.err.write(lastResort, 0, lastResort.length);
                    System.err.flush();
                } finally {
                    Runtime.getRuntime().halt(1);
                }
            }
            System.exit(1);
        });
        RealTimeJit.ownJvm();
        System.exit(run(args, new PrintWriter(System.out, true), new PrintWriter(System.err, true)));
    }

    /**
     * Runs the command line with the given output streams and returns the exit code. Running out of heap or
     * stack is one line on {@code err} and exit code 1.
     */
    public static int run(String[] args, PrintWriter out, PrintWriter err) {
        CommandLine cli = new CommandLine(new DtronCommand());
        cli.setOut(out);
        cli.setErr(err);
        cli.setParameterExceptionHandler(DtronCommand::usageError);
        cli.setExecutionStrategy(parseResult -> {
            CommandLine.ParseResult command = parseResult.subcommand();
            boolean quiet = command == null ? parseResult.isVersionHelpRequested() || parseResult.isUsageHelpRequested()
                    : command.commandSpec().userObject() instanceof CheckCommand
                    || command.commandSpec().userObject() instanceof ReportCommand;
            if (!quiet) {
                // logging (logback reads its configuration: about 0.3 s) is set up before a command that logs
                // starts, not in the middle of a timed run; check, report and --version log nothing and start faster
                LoggerFactory.getILoggerFactory();
            }
            return new CommandLine.RunLast().execute(parseResult);
        });
        cli.setExecutionExceptionHandler((e, commandLine, parseResult) -> {
            StackTraceElement[] frames = e.getStackTrace();
            commandLine.getErr().println(commandLine.getCommandSpec().qualifiedName() + ": unexpected error: " + e
                    + (frames.length == 0 ? "" : " at " + frames[0]) + " (-Ddtron.log.level=DEBUG logs the stack"
                    + " trace)");
            LoggerFactory.getLogger(DtronCommand.class).debug("internal error", e);
            return 1;
        });
        try {
            return cli.execute(withDefaultCommand(cli, args));
        } catch (OutOfMemoryError | StackOverflowError e) {
            // the stack that held the command's data has unwound: its memory is garbage, so printing works
            err.println("dtron: " + JvmLimits.describe(e));
            err.flush();
            LoggerFactory.getLogger(DtronCommand.class).debug("out of heap or stack", e);
            return 1;
        }
    }

    /**
     * Prints a usage error as its reason on one line, prefixed with the command's name, any suggestions for a
     * mistyped option or command, and where the help is; the whole usage message would bury the reason.
     */
    private static int usageError(ParameterException e, String[] args) {
        CommandLine commandLine = e.getCommandLine();
        PrintWriter err = commandLine.getErr();
        String name = commandLine.getCommandSpec().qualifiedName();
        String message = String.valueOf(e.getMessage());
        err.println(message.startsWith(name + ":") ? message : name + ": " + message);
        UnmatchedArgumentException.printSuggestions(e, err);
        err.println("see '" + name + " --help'");
        err.flush();
        return commandLine.getCommandSpec().exitCodeOnInvalidInput();
    }

    /**
     * Puts {@code run} in front of the arguments when the first one is a model file rather than an option or a
     * command: a path that exists, or a name with a dot or a path separator.
     */
    private static String[] withDefaultCommand(CommandLine cli, String[] args) {
        if (args.length == 0 || args[0].startsWith("-") || cli.getSubcommands().containsKey(args[0])
                || !looksLikeFile(args[0])) {
            return args;
        }
        String[] withRun = new String[args.length + 1];
        withRun[0] = "run";
        System.arraycopy(args, 0, withRun, 1, args.length);
        return withRun;
    }

    private static boolean looksLikeFile(String arg) {
        if (arg.contains(".") || arg.contains("/") || arg.contains(File.separator)) {
            return true;
        }
        try {
            return Files.exists(Path.of(arg));
        } catch (InvalidPathException e) {
            return false;
        }
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
