package io.dtron.cli;

import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronOptions;
import io.dtron.bridge.BusRun;
import io.dtron.bridge.BusRunSequence;
import io.dtron.engine.Adapter;
import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.engine.TestResult;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.model.delta.DeltaExtension;
import io.dtron.tron.TronBackend;
import io.dtron.tron.TronSocketAdapter;
import io.dtron.troninstaller.TronInstallation;
import io.dtron.troninstaller.TronNotFoundException;
import io.dtron.xta.ModelSyntax;
import java.io.File;
import java.io.IOException;
import java.io.PrintWriter;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.UnknownHostException;
import java.nio.file.Files;
import java.nio.file.InvalidPathException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Locale;
import java.util.Optional;
import java.util.concurrent.Callable;
import java.util.function.Supplier;
import java.util.regex.Pattern;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron run MODEL}: tests a system under test against a model with the embedded engine and prints the
 * verdict with its explanation. With {@code --sut CLASS} the system is an in-process {@link Adapter}; without,
 * the run is in real time against the adapters on a DTRON bus, through a {@link io.dtron.bridge.BusBridge}, and
 * ends with the latency of the messages and the bus counters. Exit codes: 0 passed, 2 failed, 3 inconclusive, 1
 * usage or model error.
 */
@Command(name = "run", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Test a system under test online against a model, with DTRON's engine.",
                "The model's environment chooses inputs and their timing; the system's outputs and their times are"
                        + " checked against the model. Prints the seed, a progress line every 5 s, and the verdict"
                        + " with its explanation.",
                "Without --sut the run is in real time against the adapters on a DTRON bus: inputs are published"
                        + " on the bus, messages on output channels are the outputs; the run ends with the latency"
                        + " of the messages (t2 - t1, receive minus publish time) and the bus counters.",
                "Exit code 0 PASSED, 2 FAILED, 3 INCONCLUSIVE, 1 usage or model error."})
final class RunCommand implements Callable<Integer> {
    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The model (.xml, .xta, or an Uppaal 3 .ta).")
    private Path model;

    @Option(names = "--sut", paramLabel = "CLASS[:VARIANT]",
            description = "An in-process system under test: a class implementing io.dtron.engine.Adapter,"
                    + " optionally with a variant name passed to its constructor (e.g."
                    + " io.dtron.models.lamp.SmartLamp:late), or model: the model's own implementation part,"
                    + " simulated (see --sut-seed). Without it, the adapters on the bus are tested.")
    private String sut;

    @Option(names = "--sut-seed", paramLabel = "N",
            description = "With --sut model: the seed of the simulated system's choices (default: derived from the"
                    + " run's seed).")
    private Long sutSeed;

    @Option(names = "--classpath", paramLabel = "PATH",
            description = "Jars or folders to load the system under test or the adapters from, separated by"
                    + " '${sys:path.separator}' or commas.")
    private List<String> classpath = List.of();

    @Option(names = "--cluster", paramLabel = "NAME",
            description = "Bus mode: the bus's cluster name (default: " + DtronOptions.DEFAULT_CLUSTER + ").")
    private String cluster;

    @Option(names = "--bind", paramLabel = "ADDR",
            description = "Bus mode: the network interface to bind to and to find members at; with --tron-adapter"
                    + " PORT: the address to listen on; with --live: where the live view listens (default:"
                    + " loopback).")
    private String bind;

    @Option(names = "--members", split = ",", paramLabel = "HOST[:PORT]",
            description = "Bus mode: where to look for the other members on other hosts, comma separated (default: at"
                    + " the bind address); each is probed at its bus ports from PORT (default: --port).")
    private List<String> members = List.of();

    @Option(names = "--port", paramLabel = "N",
            description = "Bus mode: the first of the ports a member may use (default: " + DtronOptions.DEFAULT_PORT
                    + ").")
    private Integer port;

    @Option(names = "--port-range", paramLabel = "N",
            description = "Bus mode: how many ports above --port are bus ports too (default: "
                    + DtronOptions.DEFAULT_PORT_RANGE + "): each member listens on one of them, on the bind address,"
                    + " and looks for the others on all of them.")
    private Integer portRange;

    @Option(names = "--testers", paramLabel = "N",
            description = "Bus mode: the run has N testers, each with its own model: this one starts the run when N - 1"
                    + " others joined it with --join (default: 1).")
    private Integer testers;

    @Option(names = "--join",
            description = "Bus mode: take part in the run another tester (with --testers) starts on this bus, judging"
                    + " this model's channels on that tester's clock.")
    private boolean join;

    @Mixin
    private BusSecretOptions.OrInsecure secret;

    @Mixin
    private NatsBusOptions nats;

    @Mixin
    private TronAdapterTimeouts tronTimeouts;

    @Mixin
    private GoalOptions goalOptions;

    @Option(names = "--wait-for-adapters", paramLabel = "channels|N",
            description = "Bus mode: start when every channel of the model is served by an adapter on the bus, as"
                    + " adapters say when they join (channels, the default), or when N members besides the tester"
                    + " are on the bus, --adapter ones included (for adapters that do not say; 0 starts at once).")
    private String waitForAdapters;

    @Option(names = "--wait-timeout", paramLabel = "SECONDS",
            description = "Bus mode: how long to wait for the adapters (default: 30).")
    private Long waitTimeout;

    @Option(names = "--adapter", paramLabel = "CLASS[:VARIANT]",
            description = "Bus mode: start a bus adapter in this JVM, a class implementing io.dtron.api.DtronAdapter"
                    + " (repeatable).")
    private List<String> adapterClasses = List.of();

    @Option(names = "--tron-adapter", paramLabel = "HOST:PORT|PORT",
            description = "The system under test is an adapter written for Uppaal TRON: connect to its socket adapter"
                    + " at HOST:PORT, or listen for it on PORT at loopback (or --bind). Its configuration defines the"
                    + " interface.")
    private String tronAdapter;

    @Option(names = "--backend", paramLabel = "engine|tron", defaultValue = "engine",
            description = "Who judges: DTRON's own engine (default), or an installed Uppaal TRON (found through"
                    + " TRON_HOME or PATH; real time only).")
    private String backend;

    @Option(names = "--interface", paramLabel = "FILE.trn",
            description = "TRON interface file; by default i_/o_ channel names give the interface.")
    private Path interfaceFile;

    @Option(names = "--virtual-time",
            description = "Run in virtual time: deterministic and as fast as the CPU allows (with --sut or"
                    + " --tron-adapter; a run on the bus is in real time).")
    private boolean virtualTime;

    @Option(names = "--seed", paramLabel = "N", description = "Seed of the random choices (default: from the clock).")
    private Long seed;

    @Option(names = "--timeout", paramLabel = "N",
            description = "Test duration in model time units (default: the interface file's, else 1000).")
    private Long timeout;

    @Option(names = "--timeunit", paramLabel = "US",
            description = "Microseconds per model time unit (default: the interface file's precision, else 1000).")
    private Long timeUnit;

    @Option(names = "--delay-policy", paramLabel = "POLICY", defaultValue = "random",
            description = "How input times are chosen: random, eager, lazy or random-bounded (default: random).")
    private String delayPolicy;

    @Option(names = "--delay-bound", paramLabel = "N|SHORT,LONG",
            description = "With --delay-policy random-bounded (and only with it, which needs it): the largest delay"
                    + " after an input's window opens, in time units; or SHORT,LONG: for each delay at most SHORT or"
                    + " at most LONG, one of the two at random (TRON's -P SHORT,LONG).")
    private String delayBound;

    @Option(names = "--delta", paramLabel = "US|auto", defaultValue = "auto",
            description = "On the bus: the reorder window, how long the tester holds its judgement for messages still"
                    + " in transit; every message is placed by the time its sender stamped on it (auto, the"
                    + " default: from the"
                    + " delays measured before the run, at least " + BusRun.AUTO_WINDOW_FLOOR_MICROS + " us, widened"
                    + " during the run when a message takes more than half of it).")
    private String delta;

    @Option(names = "--trace", paramLabel = "FILE", description = "Write every event as one JSON line to FILE; on the"
            + " bus also every message on the bus while the run lasts, in the bus's order (the other testers' channels"
            + " too; not the messages it rejects).")
    private Path trace;

    @Option(names = "--trace-max-size", paramLabel = "SIZE",
            description = "Bound the --trace file: at SIZE (bytes, or with KB, MB or GB of 1024, e.g. 10MB) it stops"
                    + " writing events; a truncated line says how many were left out, the verdict line still ends it,"
                    + " and the run's output says so.")
    private String traceMaxSize;

    @Option(names = "--junit", paramLabel = "FILE.xml",
            description = "Write the run as a JUnit XML report to FILE.xml, as Surefire, Jenkins and GitLab read it:"
                    + " one test case per run, or per goal, named by the system, the seed (and the goal); FAILED a"
                    + " failure with"
                    + " the explanation, INCONCLUSIVE an error with its reason; the seed, the coverage and the goals"
                    + " not reached as properties.")
    private Path junit;

    @Option(names = "--delta-report", paramLabel = "FILE",
            description = "Bus mode: write the delays of the run per channel and direction (inputs published to"
                    + " applied, outputs produced to received) as JSON to FILE, for dtron delta --delta-from.")
    private Path deltaReport;

    @Option(names = "--delta-from", paramLabel = "REPORT.json",
            description = "Test against the Delta-extended model: the model's observable clock bounds widened by the"
                    + " delays of a --delta-report, as dtron delta writes it.")
    private Path deltaFrom;

    @picocli.CommandLine.Mixin
    private CoverageOptions coverage = new CoverageOptions();

    @Mixin
    private ReportOptions report = new ReportOptions();

    /** The goals a stop condition's reached(N) asks about. */
    private io.dtron.engine.coverage.Goals goals = io.dtron.engine.coverage.Goals.NONE;
    /** What the run tests, as its first line names it: for {@code --junit}. */
    private String against = "";
    /** When the command started, for the time of {@code --junit}'s test case. */
    private final long startNanos = System.nanoTime();

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        boolean busMode = sut == null && tronAdapter == null;
        boolean tronBackend = parseBackend();
        checkModeOptions(busMode, tronBackend);
        DelayPolicy policy = parseDelayPolicy();
        Network network = CommandModel.network("run", model, err);
        if (network == null) {
            return 1;
        }
        TestInterface testInterface;
        goalOptions.prepare(coverage.until != null, this::usage);
        goals = goalOptions.goals();
        try {
            coverage.check(network, goals);
        } catch (IllegalArgumentException e) {
            throw usage(e.getMessage());
        }
        try {
            if (tronAdapter != null) {
                return runAgainstTronAdapter(network, policy, out, err);
            }
            testInterface = CommandModel.interfaceOf(network, interfaceFile);
        } catch (ModelException e) {
            CheckCommand.printErrors(model, e, err);
            return 1;
        } catch (IOException e) {
            err.println("dtron run: " + ioProblem(e));
            return 1;
        }
        if (testInterface.inputs().isEmpty() && testInterface.outputs().isEmpty()) {
            err.println("dtron run: " + model + " has no inputs or outputs: name channels i_x / o_y, or give"
                    + " --interface FILE.trn");
            return 1;
        }
        long unit = RunDefaults.timeUnit(timeUnit, testInterface.timeUnitMicros());
        if (deltaFrom != null) {
            try {
                network = deltaExtended(network, testInterface, unit, out);
                testInterface = CommandModel.interfaceOf(network, interfaceFile);
            } catch (ModelException e) {
                CheckCommand.printErrors(model, e, err);
                return 1;
            } catch (IOException | IllegalArgumentException e) {
                err.println("dtron run: --delta-from " + deltaFrom + ": " + e.getMessage());
                return 1;
            }
        }
        TestOptions options = testOptions(testInterface);
        if (!tronBackend) {
            OnlineTester.zenoEnvironment(network, testInterface).ifPresent(zeno -> out.println("dtron run: " + zeno));
        }
        if (!virtualTime && !tronBackend && !busMode) {
            // on a bus it is measured while the adapters are probed (prepareOnBus)
            options = options.withInputMargin(inputMargin(network, testInterface, options.timeUnitMicros(), out, err));
        }
        Judge judge;
        try {
            judge = tronBackend ? tronJudge(err) : engineJudge(network);
        } catch (TronNotFoundException e) {
            err.println("dtron run: --backend tron: " + e.getMessage());
            return 1;
        }
        try {
            return busMode ? runOnBus(network, testInterface, options, judge, out, err)
                    : runInProcess(network, testInterface, options, judge, out);
        } catch (UnsupportedModelException e) {
            err.println("dtron run: " + model + ": " + e.getMessage());
            return 1;
        } catch (TronFailure e) {
            err.println("dtron run: --backend tron: " + e.getMessage());
            return 1;
        } catch (IOException e) {
            err.println("dtron run: " + ioProblem(e));
            return 1;
        }
    }

    /** What an I/O error of the run's files says: the JUnit report's message as it is, else the trace's. */
    private String ioProblem(IOException e) {
        return e instanceof JunitFailure ? e.getMessage() : "cannot write the trace " + trace + ": " + e.getMessage();
    }

    /** The JUnit report could not be written. */
    private static final class JunitFailure extends IOException {
        private static final long serialVersionUID = 1L;

        JunitFailure(String message, IOException cause) {
            super(message, cause);
        }
    }

    /**
     * The tester's options of this command line for a model with {@code testInterface}: seed, time unit, timeout and
     * how inputs are chosen ({@code dtron mutants} runs with them too).
     */
    TestOptions testOptions(TestInterface testInterface) {
        long unit = RunDefaults.timeUnit(timeUnit, testInterface.timeUnitMicros());
        long units = RunDefaults.timeout(timeout, testInterface.timeout());
        long runSeed = RunDefaults.seed(seed);
        try {
            return withDelayBound(new TestOptions(runSeed, unit, units, parseDelayPolicy(), 0, virtualTime));
        } catch (IllegalArgumentException e) {
            throw usage(e.getMessage());
        }
    }

    /**
     * The steering of this command line's {@code --strategy}, {@code --goal}, {@code --goals}, {@code --horizon} and
     * {@code --fairness} for runs without a stop condition ({@code dtron mutants} steers its runs with it); null when
     * it asks for none.
     */
    io.dtron.engine.Steering steering() {
        return goalOptions.prepare(false, this::usage);
    }

    /** The installed TRON could not test: it did not start or connect, broke the protocol, or gave no verdict. */
    private static final class TronFailure extends RuntimeException {
        TronFailure(String message) {
            super(message);
        }
    }

    private boolean parseBackend() {
        return switch (backend.toLowerCase(Locale.ROOT)) {
            case "engine" -> false;
            case "tron" -> true;
            default -> throw usage("unknown backend '" + backend + "' (use engine or tron)");
        };
    }

    /** {@code options} with the delay bound of {@code --delay-bound}: N, or SHORT,LONG. */
    private TestOptions withDelayBound(TestOptions options) {
        boolean bounded = options.delayPolicy() == DelayPolicy.RANDOM_BOUNDED;
        if (delayBound == null) {
            if (bounded) {
                throw new IllegalArgumentException("--delay-policy random-bounded needs --delay-bound N or SHORT,LONG"
                        + " (model time units)");
            }
            return options;
        }
        if (!bounded) {
            throw new IllegalArgumentException("--delay-bound " + delayBound + " bounds the delays of --delay-policy"
                    + " random-bounded only, not of " + delayPolicy);
        }
        String bound = delayBound.strip();
        try {
            if (bound.matches("\\d+")) {
                return options.withDelayPolicy(options.delayPolicy(), Long.parseLong(bound));
            }
            if (bound.matches("\\d+,\\d+")) {
                long shortBound = Long.parseLong(bound.substring(0, bound.indexOf(',')));
                long longBound = Long.parseLong(bound.substring(bound.indexOf(',') + 1));
                if (shortBound <= longBound) {
                    return options.withShortOrLongDelays(shortBound, longBound);
                }
            }
        } catch (NumberFormatException e) {
            // too large for a number: said below
        }
        throw new IllegalArgumentException("--delay-bound " + delayBound + ": give N or SHORT,LONG with SHORT <= LONG"
                + " (model time units)");
    }

    private DelayPolicy parseDelayPolicy() {
        try {
            return DelayPolicy.valueOf(delayPolicy.toUpperCase(Locale.ROOT).replace('-', '_'));
        } catch (IllegalArgumentException e) {
            throw usage("unknown delay policy '" + delayPolicy + "' (use random, eager, lazy or random-bounded)");
        }
    }

    /** The reorder window of a bus run, in microseconds: {@code --delta}; empty for auto. */
    private java.util.OptionalLong reorderWindow() {
        if (delta.equalsIgnoreCase("auto")) {
            return java.util.OptionalLong.empty();
        }
        try {
            long micros = Long.parseLong(delta);
            if (micros >= 0) {
                return java.util.OptionalLong.of(micros);
            }
        } catch (NumberFormatException e) {
            // the message below says what is expected
        }
        throw usage("--delta takes a number of microseconds (0 or more) or auto: " + delta);
    }

    /** The JGroups bus options of this command's members (the tester's and its --adapter ones). */
    private DtronOptions.Builder jgroupsOptions() {
        DtronOptions.Builder options = DtronOptions.builder().clusterName(clusterName()).bindAddress(bindAddress());
        if (port != null) {
            options.port(port);
        }
        if (portRange != null) {
            options.portRange(portRange);
        }
        if (!members.isEmpty()) {
            options.initialMembers(initialMembers());
        }
        return options;
    }

    /** {@code --members}: each HOST or HOST:PORT, the port defaulting to --port. */
    private List<InetSocketAddress> initialMembers() {
        List<InetSocketAddress> addresses = new ArrayList<>();
        for (String member : members) {
            int colon = member.lastIndexOf(':');
            boolean hasPort = colon > 0 && member.indexOf(':') == colon; // one colon: HOST:PORT (not IPv6)
            String host = hasPort ? member.substring(0, colon) : member;
            if (host.startsWith("[") && host.endsWith("]")) {
                host = host.substring(1, host.length() - 1);
            }
            int memberPort = port != null ? port : DtronOptions.DEFAULT_PORT;
            if (hasPort) {
                String number = member.substring(colon + 1);
                if (!number.matches("\\d{1,5}") || Integer.parseInt(number) < 1 || Integer.parseInt(number) > 65535) {
                    throw usage("--members: '" + member + "' is not HOST or HOST:PORT with a port of 1 to 65535");
                }
                memberPort = Integer.parseInt(number);
            }
            try {
                addresses.add(new InetSocketAddress(InetAddress.getByName(host), memberPort));
            } catch (UnknownHostException e) {
                throw usage("--members: unknown host '" + host + "'");
            }
        }
        return addresses;
    }

    /** The bus's cluster name: {@code --cluster}, or the default. */
    private String clusterName() {
        return cluster != null ? cluster : DtronOptions.DEFAULT_CLUSTER;
    }

    /** {@code --wait-for-adapters N}: how many members to wait for; -1 for channels (the default). */
    private int adaptersWanted() {
        if (waitForAdapters == null || waitForAdapters.equalsIgnoreCase("channels")) {
            return -1;
        }
        try {
            int count = Integer.parseInt(waitForAdapters);
            if (count >= 0) {
                return count;
            }
        } catch (NumberFormatException e) {
            // reported below
        }
        throw usage("--wait-for-adapters takes 'channels' or a number of adapters (0 or more): " + waitForAdapters);
    }

    /** Rejects options that belong to another mode, and bad values of the bus options. */
    private void checkModeOptions(boolean busMode, boolean tronBackend) {
        if ("model".equals(sut) && !virtualTime) {
            throw usage("--sut model runs in virtual time: add --virtual-time (in real time the simulated system's"
                    + " timers may run late, past the end of the window it chose, and a correct system would fail)");
        }
        if (sutSeed != null && !"model".equals(sut)) {
            throw usage("--sut-seed is the seed of --sut model, the model's own implementation part; give --sut model"
                    + " or leave it out");
        }
        if (sut != null && tronAdapter != null) {
            throw usage("--sut and --tron-adapter each name the system under test; give one");
        }
        if (!busMode && (cluster != null || waitForAdapters != null || waitTimeout != null
                || !adapterClasses.isEmpty() || !members.isEmpty() || port != null || portRange != null
                || testers != null || join || deltaReport != null || secret.given())) {
            throw usage("--cluster, --members, --port, --port-range, --testers, --join, --wait-for-adapters,"
                    + " --wait-timeout, --delta-report, --key-file, --insecure and --adapter are for testing the"
                    + " adapters on a bus, without --sut or --tron-adapter");
        }
        secret.check(this::usage);
        if (join && testers != null) {
            throw usage("--testers is for the tester that starts a run; a tester that joins it (--join) leaves it out");
        }
        if (testers != null && testers < 1) {
            throw usage("--testers must be 1 or more: " + testers);
        }
        if (port != null && (port < 1 || port > 65535) || portRange != null && (portRange < 1 || portRange > 65535)) {
            throw usage("--port must be 1 to 65535 and --port-range 1 to 65535 (the bus ports: a run needs one for the"
                    + " tester and one for each adapter on this address)");
        }
        int first = port != null ? port : DtronOptions.DEFAULT_PORT;
        int range = portRange != null ? portRange : DtronOptions.DEFAULT_PORT_RANGE;
        if (first + range > 65535) {
            throw usage("--port " + first + " --port-range " + range + ": the ports " + first + ".." + (first + range)
                    + " go beyond 65535");
        }
        if (busMode) {
            initialMembers();
        }
        if (!busMode && nats.given()) {
            throw usage("--bus is the bus of the adapters; with " + (sut != null ? "--sut" : "--tron-adapter")
                    + " leave it out");
        }
        if (nats.given() && bind != null) {
            throw usage("--bind is the interface of the embedded JGroups bus; members of a NATS bus (--bus)"
                    + " connect to its servers: leave it out");
        }
        nats.check(clusterName(), this::usage);
        boolean tronListens = tronAdapter != null
                && TronAddress.parse(tronAdapter).map(a -> a.host() == null).orElse(false);
        if (bind != null && !busMode && !tronListens && report.port == null) {
            throw usage("--bind is the bus's network interface, or where --tron-adapter PORT listens; with "
                    + (sut != null ? "--sut" : "--tron-adapter HOST:PORT (DTRON connects)") + " leave it out (or give"
                    + " --live PORT: the live view listens there)");
        }
        if (report.problem() != null) {
            throw usage(report.problem());
        }
        if (tronBackend && report.given()) {
            throw usage("--report and --live show DTRON's engine's run; with --backend tron, TRON keeps its own log");
        }
        if (busMode && virtualTime) {
            throw usage("--virtual-time needs --sut or --tron-adapter: the adapters on a bus live in real time");
        }
        if (tronAdapter == null && tronTimeouts.given()) {
            throw usage("--config-timeout and --reply-timeout are for the adapter of --tron-adapter");
        }
        if (tronTimeouts.problem() != null) {
            throw usage(tronTimeouts.problem());
        }
        if (tronAdapter != null && (tronBackend || interfaceFile != null)) {
            throw usage("with --tron-adapter, DTRON's engine takes TRON's place and the adapter's configuration"
                    + " defines the interface: leave out " + (tronBackend ? "--backend tron" : "--interface"));
        }
        if (tronBackend && virtualTime) {
            throw usage("--backend tron runs in real time only; leave out --virtual-time");
        }
        if (traceMaxSize != null && trace == null) {
            throw usage("--trace-max-size bounds the --trace file: give --trace FILE too");
        }
        traceMaxBytes();
        for (String problem : new String[] {OutputFile.problem("--junit", junit, model, interfaceFile),
                OutputFile.problem("--trace", trace, model, interfaceFile),
                OutputFile.problem("--coverage", coverage.file, model, interfaceFile),
                OutputFile.problem("--report", report.file, model, interfaceFile)}) {
            if (problem != null) {
                throw usage(problem);
            }
        }
        if (tronBackend && trace != null) {
            throw usage("--trace records DTRON's engine; with --backend tron, TRON keeps its own log");
        }
        if (!busMode && !delta.equalsIgnoreCase("auto")) {
            throw usage("--delta is the reorder window of the bus; with " + (sut != null ? "--sut" : "--tron-adapter")
                    + " events reach the tester in their order: leave it out");
        }
        if (busMode) {
            reorderWindow();
        }
        if (waitForAdapters != null) {
            adaptersWanted();
        }
        if (waitTimeout != null && (waitTimeout <= 0 || waitTimeout > RunDefaults.MAX_WAIT_SECONDS)) {
            throw usage("--wait-timeout must be a positive number of seconds, at most " + RunDefaults.MAX_WAIT_SECONDS
                    + " (about 292 years): " + waitTimeout);
        }
    }

    private int runInProcess(Network network, TestInterface testInterface, TestOptions options, Judge judge,
                             PrintWriter out) throws IOException {
        Adapter adapter;
        String against = sut;
        if (sut.equals("model")) {
            long simSeed = sutSeed != null ? sutSeed : ModelSystem.seedFor(options.seed());
            adapter = new ModelSystem(network, testInterface, simSeed);
            against = "its own implementation part (--sut-seed " + simSeed + ")";
        } else {
            try {
                adapter = SystemUnderTest.create(sut, classpath());
            } catch (IllegalArgumentException e) {
                throw usage(e.getMessage());
            }
        }
        this.against = against;
        out.println("dtron run: " + model + " against " + against + ", seed " + options.seed() + ", " + options.timeout()
                + " time units of " + options.timeUnitMicros() + " us" + (virtualTime ? " in virtual time" : "")
                + judge.by());
        out.flush();
        return judge.test(testInterface, adapter, options, out).verdict().exitCode();
    }

    private int runOnBus(Network network, TestInterface testInterface, TestOptions options, Judge judge,
                         PrintWriter out,
                         PrintWriter err) throws IOException {
        String clusterName = clusterName();
        if (clusterName.isBlank()) {
            throw usage("--cluster: the cluster name is blank");
        }
        Supplier<DtronOptions.Builder> busOptions = busOptions();
        String where = busWhere();
        List<DtronAdapter> adapters = new ArrayList<>();
        try {
            List<Path> paths = classpath();
            for (String adapterClass : adapterClasses) {
                adapters.add(SystemUnderTest.createBusAdapter(adapterClass, paths));
            }
        } catch (IllegalArgumentException e) {
            throw usage(e.getMessage());
        }
        BusSession session;
        try {
            session = BusSession.open(testInterface, busOptions, join);
        } catch (IllegalArgumentException e) {
            err.println("dtron run: " + model + ": " + e.getMessage());
            return 1;
        } catch (DtronException e) {
            err.println("dtron run: " + busError(e));
            return 1;
        }
        try (session) {
            against = "the adapters on bus '" + clusterName + "'";
            BusRun busRun = session.run();
            out.println("dtron run: " + model + " on bus '" + clusterName + "' at " + where
                    + " as " + busRun.memberId() + ", seed " + options.seed() + ", " + options.timeout()
                    + " time units of " + options.timeUnitMicros() + " us in real time" + judge.by());
            out.flush();
            Duration wait = Duration.ofSeconds(waitTimeout == null ? 30 : waitTimeout);
            BusRunLines lines = new BusRunLines(out, err, busRun, clusterName, where, network, testInterface,
                    options.timeUnitMicros());
            BusRunSequence sequence = new BusRunSequence(busRun);
            Optional<BusRunSequence.Refusal> refused = sequence.otherRunFirst();
            if (refused.isPresent()) {
                lines.refused(refused.get(), wait);
                return 1;
            }
            for (int i = 0; i < adapters.size(); i++) {
                String member;
                try {
                    member = session.startAdapter(adapters.get(i));
                } catch (DtronException e) {
                    err.println("dtron run: adapter " + adapterClasses.get(i) + ": " + busError(e));
                    return 1;
                } catch (RuntimeException e) {
                    err.println("dtron run: adapter " + adapterClasses.get(i) + " failed to start: " + e);
                    return 1;
                }
                out.println("dtron run: adapter " + adapterClasses.get(i) + " joined as " + member);
            }
            // in real time with the engine, the engine warms up and the tester's lateness is measured meanwhile
            boolean warm = !parseBackend();
            refused = sequence.prepare(new BusRunSequence.Settings(wait, adaptersWanted(), testers == null ? 1
                    : testers, reorderWindow(), options.timeUnitMicros(), warm ? lines.engineWarmUp() : null), lines);
            if (refused.isPresent()) {
                lines.refused(refused.get(), wait);
                return 1;
            }
            if (lines.inputMarginMicros().isPresent()) {
                options = options.withInputMargin(lines.inputMarginMicros().getAsLong());
            }
            TestResult result = judge.test(testInterface, session.bridge(),
                    options.withReorderWindow(busRun.reorderWindowMicros()), out);
            busRun.finish(result.verdict().exitCode());
            if (deltaReport != null) {
                Files.writeString(deltaReport, BusTiming.deltaReport(model, options.timeUnitMicros(), busRun.runId(),
                        busRun.runDelays()));
            }
            session.printSummary(out);
            BusTiming.summary(busRun).forEach(out::println);
            busRun.peerVerdicts().forEach((member, code) -> out.println("tester " + member + " of this run: "
                    + (code == 0 ? "PASSED" : code == 2 ? "FAILED" : "INCONCLUSIVE")));
            out.flush();
            return result.verdict().exitCode();
        }
    }

    /**
     * The model with its observable clock bounds widened by the delays of {@code --delta-from} (see {@link
     * DeltaCommand}), loaded from the widened text.
     *
     * @throws IOException              if the report or the model cannot be read
     * @throws IllegalArgumentException if the report is not one, or names channels the model does not have
     * @throws ModelException           if the widened model does not load
     */
    private Network deltaExtended(Network network, TestInterface testInterface, long unit, PrintWriter out)
            throws IOException, ModelException {
        DeltaReport report = DeltaReport.parse(Files.readString(deltaFrom));
        Map<String, DeltaExtension.Delay> delays = report.measured();
        if (delays.isEmpty()) {
            throw new IllegalArgumentException("the report measured no channel (every count is 0)");
        }
        String text = ModelSyntax.decode(Files.readAllBytes(model));
        DeltaExtension.Result widened = DeltaExtension.extend(network, text, testInterface, delays, unit,
                "the delays of " + deltaFrom.getFileName());
        out.println("dtron run: testing against the Delta-extended model: " + widened.changes().size() + " clock bound"
                + (widened.changes().size() == 1 ? "" : "s") + " widened by the delays of " + deltaFrom
                + " (dtron delta writes the same model to a file)");
        return ModelLoader.load(model.toString(), widened.text());
    }

    /** Who judges a run: DTRON's engine, or an installed TRON. */
    private interface Judge {
        /** Tests the system under test, prints the verdict and the statistics line. */
        TestResult test(TestInterface testInterface, Adapter adapter, TestOptions options, PrintWriter out)
                throws IOException;

        /** How the first line of the run names the judge. */
        String by();
    }

    private Judge engineJudge(Network network) {
        return new Judge() {
            @Override
            public TestResult test(TestInterface testInterface, Adapter adapter, TestOptions options,
                                   PrintWriter out) throws IOException {
                return testWithEngine(network, testInterface, adapter, options, out);
            }

            @Override
            public String by() {
                return "";
            }
        };
    }

    private Judge tronJudge(PrintWriter err) throws TronNotFoundException {
        TronBackend tron = TronBackend.installed(new TronInstallation(), new LineEcho(err, "tron: "));
        return new Judge() {
            @Override
            public TestResult test(TestInterface testInterface, Adapter adapter, TestOptions options,
                                   PrintWriter out) throws IOException {
                TestResult result;
                try {
                    result = tron.run(model.toAbsolutePath(), testInterface, adapter, options);
                } catch (IllegalArgumentException e) {
                    throw usage("--backend tron: " + e.getMessage());
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    throw new TronFailure("interrupted while TRON was testing");
                } catch (IOException e) {
                    throw new TronFailure(e.getMessage());
                }
                printVerdict(result, out);
                writeJunit(result, options, null);
                return result;
            }

            @Override
            public String by() {
                return ", judged by Uppaal TRON";
            }
        };
    }

    /** Runs DTRON's tester with the trace and progress lines, and prints the verdict and the statistics. */
    private TestResult testWithEngine(Network network, TestInterface testInterface, Adapter adapter,
                                      TestOptions options, PrintWriter out) throws IOException {
        OnlineTester tester = new OnlineTester(network, testInterface, adapter, options);
        coverage.configure(tester, goals);
        goalOptions.apply(tester, out, this::usage);
        TestResult result;
        ReportOptions.Session reporting;
        try {
            reporting = report.open(model, network, options, bindAddress(), out);
        } catch (IOException e) {
            throw usage(e.getMessage());
        }
        try (Progress progress = new Progress(out, options)) {
            tester.addListener(progress);
            if (reporting != null) {
                tester.addListener(reporting.recorder());
            }
            result = JsonTrace.run(tester, trace, model, options, adapter, traceMaxBytes(), note -> {
                out.println("dtron run: " + note);
                out.flush();
            });
        } finally {
            if (reporting != null) {
                reporting.stopLive();
            }
        }
        printVerdict(result, out);
        coverage.report(result, out, spec.commandLine().getErr());
        goalOptions.report(tester, options.timeUnitMicros(), out);
        writeJunit(result, options, tester.steeringReport());
        if (reporting != null) {
            reporting.write(out, spec.commandLine().getErr());
        }
        return result;
    }

    /**
     * {@code --junit}: writes the run's JUnit XML report, with what it printed last as the suite's output.
     *
     * @throws IOException if the report cannot be written
     */
    private void writeJunit(TestResult result, TestOptions options, io.dtron.engine.SteeringReport steering)
            throws IOException {
        if (junit == null) {
            return;
        }
        long unit = options.timeUnitMicros();
        String output = result.verdict() + ": " + result.explanation() + "\nstatistics: " + result.statisticsLine()
                + " (seed verdict inputs outputs duration-us)\n" + (result.coverage() == null ? ""
                : result.coverage().summary() + "\n");
        try {
            JunitXml.write(junit, "dtron run " + model, JunitXml.className("dtron.", model),
                    JunitXml.cases(result, against, steering, unit), JunitXml.properties(model.toString(), against,
                    result, unit, options.timeout(), options.virtualTime(), steering),
                    (System.nanoTime() - startNanos) / 1e9, output);
        } catch (IOException e) {
            throw new JunitFailure("cannot write the JUnit report " + junit + ": " + OutputFile.reason(e), e);
        }
    }

    /** {@code --trace-max-size} in bytes: N, or N with KB, MB or GB (of 1024); unbounded without it. */
    private long traceMaxBytes() {
        if (traceMaxSize == null) {
            return JsonTrace.UNBOUNDED;
        }
        java.util.regex.Matcher m = Pattern.compile("(\\d{1,12})\\s*([KMG]?B?)").matcher(traceMaxSize.strip()
                .toUpperCase(Locale.ROOT));
        if (m.matches()) {
            int shift = switch (m.group(2).isEmpty() ? 'B' : m.group(2).charAt(0)) {
                case 'K' -> 10;
                case 'M' -> 20;
                case 'G' -> 30;
                default -> 0;
            };
            long size = Long.parseLong(m.group(1));
            if (size > 0 && size <= Long.MAX_VALUE >> shift) {
                return size << shift;
            }
        }
        throw usage("--trace-max-size " + traceMaxSize + ": give a positive size in bytes, or with KB, MB or GB"
                + " (e.g. 10MB)");
    }

    private static void printVerdict(TestResult result, PrintWriter out) {
        out.println(result.verdict() + ": " + result.explanation());
        out.println("statistics: " + result.statisticsLine() + " (seed verdict inputs outputs duration-us)");
        out.flush();
    }

    /**
     * {@code --tron-adapter}: DTRON's engine in TRON's place. The adapter connects (or is connected to), registers
     * its channels, variables, time unit and timeout, and is then tested.
     */
    private int runAgainstTronAdapter(Network network, DelayPolicy policy, PrintWriter out, PrintWriter err)
            throws IOException {
        TronAddress address = TronAddress.parse(tronAdapter).orElseThrow(() -> usage("--tron-adapter "
                + tronAdapter + ": give HOST:PORT to connect to the adapter, or PORT to listen for it"));
        TronSocketAdapter.Settings settings = tronTimeouts.applyTo(TronSocketAdapter.Settings.forRealTime()
                .withVirtualTime(virtualTime));
        long runSeed = RunDefaults.seed(seed);
        TronSocketAdapter adapter;
        try {
            if (address.host() == null) {
                InetAddress listenAt = bindAddress();
                ServerSocket listening;
                try {
                    listening = new ServerSocket(address.port(), 1, listenAt);
                } catch (IOException e) {
                    err.println("dtron run: --tron-adapter " + tronAdapter + ": cannot listen for the adapter on "
                            + listenAt.getHostAddress() + ":" + address.port() + ": " + e.getMessage()
                            + " (give another port, or 0 for any free one)");
                    return 1;
                }
                try (ServerSocket server = listening) {
                    out.println("dtron run: waiting for the TRON adapter on " + listenAt.getHostAddress() + ":"
                            + server.getLocalPort());
                    out.flush();
                    adapter = TronSocketAdapter.accept(server, network, settings);
                }
            } else {
                adapter = TronSocketAdapter.connect(address.host(), address.port(), network, settings);
            }
        } catch (IOException e) {
            err.println("dtron run: the TRON adapter's configuration failed: " + e.getMessage());
            return 1;
        }
        try {
            TestInterface testInterface = adapter.testInterface();
            Long adapterUnit = testInterface.timeUnitMicros();
            if (timeUnit != null && adapterUnit != null && !timeUnit.equals(adapterUnit)) {
                String reason = "--timeunit " + timeUnit + " differs from the time unit the adapter set, "
                        + adapterUnit + " us; leave --timeunit out";
                adapter.refuse("DTRON refuses the start: " + reason);
                err.println("dtron run: " + reason);
                return 1;
            }
            long unit = RunDefaults.timeUnit(adapterUnit, timeUnit);
            long units = RunDefaults.timeout(timeout, testInterface.timeout());
            TestOptions options;
            try {
                options = withDelayBound(new TestOptions(runSeed, unit, units, policy, 0, virtualTime));
                if (!virtualTime) {
                    options = options.withInputMargin(inputMargin(network, testInterface, unit, out, err));
                }
            } catch (IllegalArgumentException e) {
                String reason = e.getMessage() + " (timeout from " + (timeout != null ? "--timeout"
                        : testInterface.timeout() != null ? "the adapter" : "the default") + ", time unit from "
                        + (adapterUnit != null ? "the adapter" : timeUnit != null ? "--timeunit" : "the default") + ")";
                adapter.refuse("DTRON refuses the start: " + reason);
                err.println("dtron run: " + reason);
                return 1;
            }
            against = "the TRON adapter at " + adapter.remote();
            out.println("dtron run: " + model + " against the TRON adapter at " + adapter.remote() + ", seed "
                    + runSeed + ", " + units + " time units of " + unit + " us"
                    + (virtualTime ? " in virtual time" : ""));
            OnlineTester.zenoEnvironment(network, testInterface).ifPresent(zeno -> out.println("dtron run: " + zeno));
            out.flush();
            return testWithEngine(network, testInterface, adapter, options, out).verdict().exitCode();
        } catch (UnsupportedModelException e) {
            // the engine refused the interface before the test started: the adapter's start gets the reason
            adapter.refuse("DTRON refuses the start: " + e.getMessage());
            err.println("dtron run: " + model + ": " + e.getMessage());
            return 1;
        } finally {
            adapter.close();
        }
    }

    /** The input margin of a real-time run, measured and said as {@link SchedulingDelay#inputMarginForRun} does. */
    private static long inputMargin(Network network, TestInterface testInterface, long unitMicros, PrintWriter out,
            PrintWriter err) {
        return SchedulingDelay.inputMarginForRun("run", network, testInterface, unitMicros, "--virtual-time", line -> {
            out.println(line);
            out.flush();
        }, err);
    }

    /** The {@code --classpath} entries: every value split at the platform's path separator and at commas. */
    private List<Path> classpath() {
        List<Path> paths = new ArrayList<>();
        for (String value : classpath) {
            for (String entry : value.split("[," + Pattern.quote(File.pathSeparator) + "]")) {
                if (entry.isBlank()) {
                    continue;
                }
                try {
                    paths.add(Path.of(entry));
                } catch (InvalidPathException e) {
                    throw usage("--classpath entry '" + entry + "' is not a path: " + e.getReason());
                }
            }
        }
        return paths;
    }

    /** Where the bus is, for messages: the NATS servers or the JGroups interface. */
    private String busWhere() {
        return nats.given() ? String.join(",", nats.servers(this::usage)) : bindAddress().getHostAddress();
    }

    /**
     * Makes the options of the members of this JVM on the bus, with the bus's secret of {@code --key-file} or the
     * default key file, or none ({@code --insecure}); reads the NATS secret files once, now.
     */
    private Supplier<DtronOptions.Builder> busOptions() {
        String cluster = clusterName();
        Supplier<DtronOptions.Builder> transport = nats.given() ? nats.memberOptions(cluster, this::usage)
                : this::jgroupsOptions;
        return () -> secret.apply(transport.get());
    }

    /** {@code --bind}, else loopback: the bus's interface, or where {@code --tron-adapter PORT} listens. */
    private InetAddress bindAddress() {
        if (bind == null) {
            return InetAddress.getLoopbackAddress();
        }
        try {
            return InetAddress.getByName(bind);
        } catch (UnknownHostException e) {
            throw usage("--bind: unknown address '" + bind + "'");
        }
    }

    /** {@code HOST:PORT} (connect) or {@code PORT} (listen; 0 for any free port). */
    record TronAddress(String host, int port) {
        static Optional<TronAddress> parse(String text) {
            int colon = text.lastIndexOf(':');
            String host = colon < 0 ? null : text.substring(0, colon);
            if (host != null && host.startsWith("[") && host.endsWith("]")) {
                host = host.substring(1, host.length() - 1);
            }
            String port = text.substring(colon + 1);
            if (!port.matches("\\d{1,5}") || Integer.parseInt(port) > 65535 || host != null && host.isBlank()
                    || host != null && Integer.parseInt(port) == 0) {
                return Optional.empty();
            }
            return Optional.of(new TronAddress(host, Integer.parseInt(port)));
        }
    }

    private static String busError(DtronException e) {
        return e.getMessage() + (e.getCause() == null ? "" : ": " + e.getCause().getMessage());
    }

    private ParameterException usage(String message) {
        return new ParameterException(spec.commandLine(), "dtron run: " + message);
    }
}
