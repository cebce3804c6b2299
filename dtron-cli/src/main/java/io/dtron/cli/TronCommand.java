package io.dtron.cli;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.tron.TronClockServer;
import io.dtron.tron.TronSocketAdapter;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.Writer;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron tron [TRON's options] MODEL -- HOST PORT} (or {@code -- PORT} to listen): DTRON in TRON's place, a
 * drop-in for TRON's command line with its socket adapter. The adapter's configuration defines the interface; the
 * run prints the seed, the verdict as {@code TEST PASSED|FAILED|INCONCLUSIVE: explanation} and exits 0, 2 or 3 (1
 * for a usage, model or configuration error). Every TRON option DTRON knows is honoured or refused with a message;
 * see the site page {@code tron.md} for the table.
 */
@Command(name = "tron", mixinStandardHelpOptions = true, versionProvider = DtronCommand.Version.class,
        exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1, sortOptions = false,
        description = {"DTRON in Uppaal TRON's place: test a system through its TRON socket adapter, unchanged.",
                "Takes TRON's options, so that a script written for TRON runs DTRON by changing the program name:"
                        + " dtron tron -I SocketAdapter -P 10,200 -F 300 LightContr.xml -- localhost 9999",
                "-- HOST PORT connects to an adapter that listens (as TRON's samples do); -- PORT listens for one.",
                "Exit code 0 PASSED, 2 FAILED, 3 INCONCLUSIVE, 1 usage, model or adapter configuration error."})
final class TronCommand implements Callable<Integer> {
    /** With -Q and -- HOST PORT: how long the adapter may take to open its port (TRON's samples open it late). */
    private static final Duration ADAPTER_PORT_WAIT = Duration.ofSeconds(30);

    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The model (.xml, .xta, or an Uppaal 3 .ta).")
    private Path model;

    @Parameters(index = "1..*", arity = "0..2", paramLabel = "HOST PORT | PORT",
            description = "After --: the adapter's address to connect to, or a port to listen on (0: any free port).")
    private List<String> address = new ArrayList<>();

    @Option(names = "-I", paramLabel = "ADAPTER", defaultValue = "SocketAdapter",
            description = "TRON's adapter: only SocketAdapter (the default) is supported.")
    private String adapterName;

    @Option(names = "-P", paramLabel = "DELAY", defaultValue = "random",
            description = "Delay choice: random (default), eager, lazy, MAX (random, at most MAX units after an"
                    + " input's window opens) or SHORT,LONG (as TRON: for each delay, at most SHORT or at most LONG"
                    + " units, one of the two at random).")
    private String delay;

    @Option(names = "-F", paramLabel = "UNITS",
            description = "How long to test, in model time units (default: the adapter's timeout, else 1000).")
    private Long future;

    @Option(names = {"-U", "-u"}, paramLabel = "UNCERTAINTY",
            description = "TRON's observation uncertainty: accepted and not applied (outputs are time-stamped on"
                    + " arrival; see the documentation).")
    private String uncertainty;

    @Option(names = "-v", paramLabel = "LEVEL", defaultValue = "0",
            description = "Verbosity: 0 the settings and the verdict, 1 also every input and output, 2 also the"
                    + " interface the adapter registered.")
    private int verbosity;

    @Option(names = "-X", paramLabel = "SEED", description = "Seed of the random choices (default: from the clock).")
    private Long seed;

    @Option(names = "-o", paramLabel = "FILE", description = "Also write everything printed to FILE.")
    private Path logFile;

    @Option(names = {"-S", "--stats"}, paramLabel = "FILE",
            description = "Append TRON's statistics line 'seed verdict #inputs #outputs duration' to FILE (the"
                    + " duration in microseconds).")
    private Path statsFile;

    @Option(names = "-q", description = "Quiet: print the verdict line only.")
    private boolean quiet;

    @Option(names = "-Q", paramLabel = "PORT",
            description = "Serve TRON's virtual clock on PORT (0: any free port, printed) and run in virtual time, as"
                    + " TRON's -Q does: start the adapter with its clock at this port (TRON's samples: -C localhost"
                    + " PORT). With -- HOST PORT, DTRON waits up to 30 s for the adapter's port to open.")
    private String clockPort;

    @Option(names = "--virtual-time",
            description = "Run in virtual time: the adapter must acknowledge events (TRON's virtual-time protocol)"
                    + " or use DTRON's shared virtual clock.")
    private boolean virtualTime;

    @Option(names = "--bind", paramLabel = "ADDRESS", defaultValue = "127.0.0.1",
            description = "With -- PORT: the address to listen on (default 127.0.0.1; 0.0.0.0 for every interface).")
    private String bind;

    @Mixin
    private TronAdapterTimeouts timeouts;

    @Option(names = "--trace", paramLabel = "FILE", description = "Write every event as one JSON line to FILE.")
    private Path trace;

    /** Prints to standard output and, with -o, to the log file. */
    private static final class Printer implements AutoCloseable {
        private final PrintWriter out;
        private final Writer log;

        Printer(PrintWriter out, Writer log) {
            this.out = out;
            this.log = log;
        }

        synchronized void println(String line) {
            out.println(line);
            out.flush();
            if (log != null) {
                try {
                    log.write(line);
                    log.write(System.lineSeparator());
                    log.flush();
                } catch (IOException e) {
                    out.println("dtron tron: cannot write the log: " + OutputFile.reason(e));
                }
            }
        }

        @Override
        public void close() throws IOException {
            if (log != null) {
                log.close();
            }
        }
    }

    @Override
    public Integer call() {
        PrintWriter err = spec.commandLine().getErr();
        String usage = checkUsage();
        if (usage != null) {
            throw usage(usage);
        }
        DelayChoice choice;
        try {
            choice = DelayChoice.parse(delay);
        } catch (IllegalArgumentException e) {
            throw usage(e.getMessage());
        }
        Network network = CommandModel.network("tron", model, err);
        if (network == null) {
            return 1;
        }
        if (!quiet) {
            notes(err);
        }
        long runSeed = RunDefaults.seed(seed);
        try (Printer printer = new Printer(spec.commandLine().getOut(), logFile == null ? null
                : Files.newBufferedWriter(logFile, StandardCharsets.UTF_8))) {
            return run(network, choice, runSeed, printer, err);
        } catch (IOException e) {
            err.println("dtron tron: cannot write " + logFile + ": " + OutputFile.reason(e));
            return 1;
        }
    }

    private ParameterException usage(String message) {
        return new ParameterException(spec.commandLine(), "dtron tron: " + message);
    }

    private String checkUsage() {
        // first: "-Q MODEL" (DTRON's old quiet flag) leaves the model's place to what follows
        if (clockPort != null && parsePort(clockPort) < 0) {
            return "-Q " + clockPort + ": -Q takes the port of TRON's virtual clock server (0 to 65535), as TRON's"
                    + " does; for quiet output use -q";
        }
        if (!adapterName.equals("SocketAdapter")) {
            return "-I " + adapterName + " is not supported: DTRON speaks TRON's socket adapter protocol only (-I"
                    + " SocketAdapter); for a system in the JVM use dtron run --sut";
        }
        if (address.isEmpty() || address.size() > 2) {
            return (address.isEmpty() ? "give" : "too many arguments after the model: give") + " the adapter's"
                    + " address after the model: -- HOST PORT to connect, or -- PORT to listen";
        }
        if (port() < 0) {
            return "'" + address.get(address.size() - 1) + "' is not a port (0 to 65535)";
        }
        if (uncertainty != null && !uncertainty.matches("\\d+(\\.\\d+)?(,\\d+(\\.\\d+)?)?")) {
            return "-U " + uncertainty + ": give a number of model time units, or MIN,MAX";
        }
        if (verbosity < 0) {
            return "-v " + verbosity + ": the verbosity is 0 or more";
        }
        if (future != null && future <= 0) {
            return "-F " + future + ": the test duration must be a positive number of model time units";
        }
        if (timeouts.problem() != null) {
            return timeouts.problem();
        }
        return null;
    }

    private static int parsePort(String text) {
        try {
            int port = Integer.parseInt(text);
            return port >= 0 && port <= 65535 ? port : -1;
        } catch (NumberFormatException e) {
            return -1;
        }
    }

    private int port() {
        return parsePort(address.get(address.size() - 1));
    }

    private void notes(PrintWriter err) {
        if (uncertainty != null) {
            err.println("dtron tron: note: -U " + uncertainty + " is accepted and not applied: DTRON time-stamps each"
                    + " output when it arrives and checks it against the model at the precision of the time unit");
        }
        err.flush();
    }

    private int run(Network network, DelayChoice choice, long runSeed, Printer printer, PrintWriter err) {
        if (clockPort == null) {
            return run(network, choice, runSeed, printer, err, null);
        }
        TronClockServer clock;
        try {
            clock = TronClockServer.open(InetAddress.getByName(bind), parsePort(clockPort));
        } catch (IOException e) {
            err.println("dtron tron: -Q " + clockPort + ": cannot serve the virtual clock on " + bind + ":" + clockPort
                    + ": " + e.getMessage() + " (give another port, or 0 for any free one)");
            return 1;
        }
        try (clock) {
            if (!quiet) {
                printer.println("dtron tron: virtual clock server on " + clock.address());
            }
            return run(network, choice, runSeed, printer, err, clock);
        }
    }

    private int run(Network network, DelayChoice choice, long runSeed, Printer printer, PrintWriter err,
                    TronClockServer clock) {
        boolean virtual = virtualTime || clock != null;
        boolean listen = address.size() == 1;
        String where = listen ? "listening for the adapter" : "connecting to " + address.get(0) + ":" + port();
        if (!quiet) {
            printer.println("dtron tron: " + model + ", random seed " + runSeed + ", " + where
                    + (virtual ? ", virtual time" : ""));
        }
        TronSocketAdapter.Settings settings = timeouts.applyTo(TronSocketAdapter.Settings.forRealTime()
                .withVirtualTime(virtual));
        ServerSocket server = null;
        if (listen) {
            try {
                server = new ServerSocket(port(), 1, InetAddress.getByName(bind));
            } catch (IOException e) {
                err.println("dtron tron: -- " + port() + ": cannot listen for the adapter on " + bind + ":" + port()
                        + ": " + e.getMessage() + " (give another port after --, or 0 for any free one)");
                return 1;
            }
        }
        TronSocketAdapter adapter;
        try {
            if (listen) {
                adapter = acceptOne(server, network, settings, printer);
            } else if (clock != null) {
                adapter = TronSocketAdapter.connectWhenOpen(address.get(0), port(), network, settings,
                        ADAPTER_PORT_WAIT);
            } else {
                adapter = TronSocketAdapter.connect(address.get(0), port(), network, settings);
            }
        } catch (IOException e) {
            err.println("dtron tron: the adapter's configuration failed: " + e.getMessage() + (clock == null ? ""
                    : " (" + clock.threadsConnected() + " of its threads connected to the virtual clock at "
                    + clock.address() + ")"));
            return 1;
        }
        try {
            if (clock != null) {
                adapter.useClockServer(clock);
            }
            return test(network, choice, runSeed, printer, err, adapter, virtual);
        } finally {
            adapter.close();
        }
    }

    private int test(Network network, DelayChoice choice, long runSeed, Printer printer, PrintWriter err,
                     TronSocketAdapter adapter, boolean virtual) {
        TestInterface ti = adapter.testInterface();
        long unit = RunDefaults.timeUnit(ti.timeUnitMicros());
        long units = RunDefaults.timeout(future, ti.timeout());
        if (!quiet) {
            printer.println("dtron tron: adapter " + adapter.remote() + ": " + units + " time units of " + unit + " us"
                    + (verbosity >= 2 ? "; " + describe(ti) : ""));
        }
        TestOptions options;
        try {
            options = new TestOptions(runSeed, unit, units, choice.policy(), choice.bound(), virtual);
            if (choice.shortBound() > 0) {
                options = options.withShortOrLongDelays(choice.shortBound(), choice.bound());
            }
            if (!virtual) {
                options = options.withInputMargin(SchedulingDelay.inputMarginForRun("tron", network, ti, unit,
                        "-Q PORT", quiet ? null : printer::println, err));
            }
        } catch (IllegalArgumentException e) {
            String reason = e.getMessage() + " (timeout from " + (future != null ? "-F" : ti.timeout() != null
                    ? "the adapter" : "the default") + ", time unit from " + (ti.timeUnitMicros() != null
                    ? "the adapter" : "the default") + ")";
            adapter.refuse("DTRON refuses the start: " + reason);
            err.println("dtron tron: " + reason);
            return 1;
        }
        if (!quiet) {
            OnlineTester.zenoEnvironment(network, ti).ifPresent(zeno -> printer.println("dtron tron: " + zeno));
        }
        OnlineTester tester = new OnlineTester(network, ti, adapter, options);
        if (verbosity >= 1 && !quiet) {
            tester.addListener(new EventPrinter(printer, unit));
        }
        TestResult result;
        try {
            result = JsonTrace.run(tester, trace, model, options);
        } catch (UnsupportedModelException e) {
            // the engine refused the interface before the test started: the adapter's start gets the reason
            adapter.refuse("DTRON refuses the start: " + e.getMessage());
            err.println("dtron tron: " + model + ": " + e.getMessage());
            return 1;
        } catch (IOException e) {
            err.println("dtron tron: cannot write the trace " + trace + ": " + OutputFile.reason(e));
            return 1;
        }
        printer.println("TEST " + result.verdict() + ": " + result.explanation());
        if (statsFile != null) {
            try {
                Files.writeString(statsFile, result.statisticsLine() + System.lineSeparator(),
                        StandardCharsets.UTF_8, StandardOpenOption.CREATE, StandardOpenOption.APPEND);
            } catch (IOException e) {
                err.println("dtron tron: cannot write the statistics " + statsFile + ": " + OutputFile.reason(e));
                return 1;
            }
        }
        return result.verdict().exitCode();
    }

    private TronSocketAdapter acceptOne(ServerSocket listening, Network network, TronSocketAdapter.Settings settings,
            Printer printer) throws IOException {
        try (ServerSocket server = listening) {
            if (!quiet) {
                printer.println("dtron tron: waiting for the adapter on " + server.getInetAddress().getHostAddress()
                        + ":" + server.getLocalPort());
            }
            return TronSocketAdapter.accept(server, network, settings);
        }
    }

    private static String describe(TestInterface ti) {
        return "inputs " + CheckCommand.channels(ti.inputs()) + "; outputs " + CheckCommand.channels(ti.outputs());
    }

    /**
     * TRON's {@code -P} value as DTRON's delay policy: {@code SHORT,LONG} bounds each delay by SHORT or by LONG, one
     * of the two at random, as TRON's manual says ("the choice of a short or a long delay is random"); shortBound 0
     * for the other values.
     */
    record DelayChoice(DelayPolicy policy, long shortBound, long bound) {
        static DelayChoice parse(String text) {
            String t = text.strip().toLowerCase(Locale.ROOT);
            switch (t) {
                case "random": return new DelayChoice(DelayPolicy.RANDOM, 0, 0);
                case "eager": return new DelayChoice(DelayPolicy.EAGER, 0, 0);
                case "lazy": return new DelayChoice(DelayPolicy.LAZY, 0, 0);
                default: break;
            }
            if (t.matches("\\d{1,9}")) {
                return new DelayChoice(DelayPolicy.RANDOM_BOUNDED, 0, Long.parseLong(t));
            }
            if (t.matches("\\d{1,9},\\d{1,9}")) {
                String[] parts = t.split(",");
                long shortBound = Long.parseLong(parts[0]);
                long longBound = Long.parseLong(parts[1]);
                if (shortBound <= longBound) {
                    return new DelayChoice(DelayPolicy.RANDOM_BOUNDED, shortBound, longBound);
                }
            }
            throw new IllegalArgumentException("-P " + text + ": use random, eager, lazy, MAX or SHORT,LONG with SHORT"
                    + " <= LONG (model time units)");
        }
    }

    /** Prints every input and output with its time, at verbosity 1 and more. */
    private static final class EventPrinter implements TestListener {
        private final Printer printer;
        private final long unit;

        EventPrinter(Printer printer, long unit) {
            this.printer = printer;
            this.unit = unit;
        }

        @Override
        public void inputApplied(Event input, long micros) {
            printer.println(String.format(Locale.ROOT, "t=%.3f input %s", micros / (double) unit, input));
        }

        @Override
        public void outputObserved(Event output, long micros) {
            printer.println(String.format(Locale.ROOT, "t=%.3f output %s", micros / (double) unit, output));
        }
    }
}
