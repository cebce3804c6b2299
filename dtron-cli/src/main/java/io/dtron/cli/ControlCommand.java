package io.dtron.cli;

import io.dtron.api.DtronException;
import io.dtron.api.DtronOptions;
import io.dtron.bridge.BusBridge;
import io.dtron.bridge.BusRunSequence;
import io.dtron.engine.Adapter;
import io.dtron.engine.Event;
import io.dtron.engine.TestOptions;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.control.ControlListener;
import io.dtron.engine.control.ControlPolicy;
import io.dtron.engine.control.ControlResult;
import io.dtron.engine.control.Controller;
import io.dtron.engine.control.ModelVersion;
import io.dtron.engine.control.SafeAction;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.engine.sim.Mutant;
import io.dtron.engine.sim.Mutants;
import io.dtron.engine.verify.QueryException;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.PrintWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.Callable;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.Supplier;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron control MODEL}: the model as controller. Parses the options, builds the plant (the model's own plant
 * part, or the plant on a bus through a {@link BusBridge}, whose run owner prepares and keeps the run) and the {@link
 * Controller}, watches the file of new model versions, and prints what happens and the summary; the engine runs the
 * control.
 */
@Command(name = "control", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Run the model as a controller: DTRON sends the commands (i_ channels) the model's controller"
                + " part chooses and takes the plant's readings (o_ channels) as the model allows them.",
                "A plant that deviates from the model raises an alarm; the controller then takes the safe action"
                        + " (--safe-action, --safe-location) and the run ends. A new model version (--reload-from,"
                        + " --reload-from-bus) is checked with its queries and taken at the next reset point.",
                "The plant: --plant model (the model's own plant part, in this process, in virtual time), or a"
                        + " plant on a bus (--cluster NAME, JGroups on loopback; --bus nats://HOST:PORT, NATS), in real"
                        + " time.",
                "Exit code 0 when the run lasted its duration, 2 after an alarm, 3 when it stopped for another reason,"
                        + " 1 usage or model error."})
final class ControlCommand implements Callable<Integer> {
    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The closed model (.xml, .xta, or an Uppaal 3 .ta).")
    private Path model;

    @Option(names = "--interface", paramLabel = "FILE.trn",
            description = "Take commands (inputs) and readings (outputs) from a TRON interface file instead of i_/o_.")
    private Path interfaceFile;

    @Option(names = "--plant", paramLabel = "model",
            description = "The plant: 'model', the model's own plant part simulated in this process (without a bus).")
    private String plant;

    @Option(names = "--junit", paramLabel = "FILE.xml",
            description = "Write the run as a JUnit XML report to FILE.xml: one test case, an alarm a failure (with"
                    + " the safe action taken), a run stopped for another reason an error; the settings and counts as"
                    + " properties.")
    private Path junit;

    @Option(names = "--plant-mutant", paramLabel = "N",
            description = "With --plant model: mutant N of the plant part instead (the numbers dtron mutants prints),"
                    + " e.g. one whose reading is dropped: a stalling plant.")
    private Integer plantMutant;

    @Option(names = "--plant-seed", paramLabel = "N",
            description = "With --plant model: the seed of the plant's choices (default: derived from --seed).")
    private Long plantSeed;

    @Option(names = "--duration", paramLabel = "UNITS", required = true,
            description = "How long the run lasts, in model time units.")
    private long duration;

    @Option(names = "--policy", paramLabel = "eager|random|goal", defaultValue = "eager",
            description = "How commands are chosen: as early as allowed (default), at random, or toward --goal.")
    private String policy;

    @Option(names = "--goal", paramLabel = "'E<> P'", description = "A goal of the goal policy (repeatable).")
    private List<String> goals = new ArrayList<>();

    @Option(names = "--safe-action", paramLabel = "CHANNEL",
            description = "The command sent after an alarm (i_stop); the model's plant must take it anywhere.")
    private String safeAction;

    @Option(names = "--safe-location", paramLabel = "PROCESS.LOCATION",
            description = "After an alarm, the command that the model's edges into this location send.")
    private String safeLocation;

    @Option(names = "--reload-from", paramLabel = "FILE",
            description = "A new version of the model: checked (it loads, its queries hold) when the run starts and"
                    + " whenever the file changes, and taken at the next reset point; refused with the reason otherwise.")
    private Path reloadFrom;

    @Option(names = "--reload-from-bus",
            description = "On a bus with a secret: new versions of the model from the bus (channel dtron_model, as"
                    + " dtron reload sends them), checked and taken as those of --reload-from; what became of each is"
                    + " published back (dtron_model_outcome).")
    private boolean reloadFromBus;

    @Option(names = "--virtual-time", description = "Run in virtual time: deterministic, as fast as the CPU allows"
            + " (--plant model needs it).")
    private boolean virtualTime;

    @Option(names = "--seed", paramLabel = "N", description = "Seed of the random choices (default: from the clock).")
    private Long seed;

    @Option(names = "--timeunit", paramLabel = "US",
            description = "Microseconds per model time unit (default: the interface file's precision, else 1000).")
    private Long timeUnit;

    @Option(names = "--cluster", paramLabel = "NAME",
            description = "The plant is on the bus of this name (default '" + DtronOptions.DEFAULT_CLUSTER + "' with"
                    + " --bus): the embedded JGroups bus on loopback, or the NATS bus of --bus.")
    private String cluster;

    @Mixin
    private NatsBusOptions nats;

    @Mixin
    private BusSecretOptions.OrInsecure secret;

    @Option(names = "--wait-timeout", paramLabel = "SECONDS",
            description = "On the bus: how long to wait for the plant to serve every command and reading (default 30).")
    private Long waitTimeout;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        try {
            return control(out, err);
        } catch (ModelException e) {
            CheckCommand.printErrors(model, e, err);
            return 1;
        } catch (UnsupportedModelException | QueryException e) {
            err.println("dtron control: " + model + ": " + e.getMessage());
            return 1;
        } catch (java.io.UncheckedIOException e) {
            err.println("dtron control: " + e.getMessage());
            return 1;
        } finally {
            out.flush();
            err.flush();
        }
    }

    private int control(PrintWriter out, PrintWriter err) throws ModelException {
        boolean onBus = cluster != null || nats.given();
        if (onBus) {
            if (plant != null || plantMutant != null || plantSeed != null) {
                throw usage("the plant is on the bus (--cluster, --bus): leave out --plant, --plant-mutant and"
                        + " --plant-seed");
            }
            if (virtualTime) {
                throw usage("a plant on the bus runs in real time: leave out --virtual-time");
            }
            if (waitTimeout != null && (waitTimeout <= 0 || waitTimeout > RunDefaults.MAX_WAIT_SECONDS)) {
                throw usage("--wait-timeout must be a positive number of seconds, at most "
                        + RunDefaults.MAX_WAIT_SECONDS + ": " + waitTimeout);
            }
            if (cluster != null && cluster.isBlank()) {
                throw usage("--cluster: the bus name is blank");
            }
            secret.check(this::usage);
            if (reloadFromBus && secret.insecure()) {
                throw usage("--reload-from-bus takes model versions only from a bus with a secret: leave out"
                        + " --insecure");
            }
            nats.check(clusterName(), this::usage);
        } else {
            if (!"model".equals(plant)) {
                throw usage(plant == null ? "name the plant: --plant model (the model's own plant part), or a bus"
                        + " (--cluster NAME, --bus nats://HOST:PORT)" : "--plant must be 'model' (the model's own"
                        + " plant part), or leave it out and give the plant's bus (--cluster, --bus)");
            }
            if (!virtualTime) {
                throw usage("--plant model runs in virtual time: add --virtual-time (a plant in this process is"
                        + " simulated on the controller's clock; real time is for a plant on the bus, --cluster or"
                        + " --bus)");
            }
            if (waitTimeout != null || secret.given() || reloadFromBus) {
                throw usage("--wait-timeout, --key-file, --insecure and --reload-from-bus are for a plant on the bus"
                        + " (--cluster, --bus)");
            }
        }
        if (duration <= 0) {
            throw usage("--duration must be a positive number of time units: " + duration);
        }
        String junitProblem = OutputFile.problem("--junit", junit, model, interfaceFile, reloadFrom);
        if (junitProblem != null) {
            throw usage(junitProblem);
        }
        if (safeAction != null && safeLocation != null) {
            throw usage("give --safe-action or --safe-location, not both");
        }
        if (reloadFrom != null && (reloadFrom.toString().isEmpty() || Files.isDirectory(reloadFrom))) {
            throw usage("--reload-from " + reloadFrom + ": give the file new versions are written to, not a folder");
        }
        if (reloadFrom != null && !Files.isDirectory(reloadFrom.toAbsolutePath().getParent())) {
            throw usage("--reload-from " + reloadFrom + ": its folder does not exist");
        }
        ControlPolicy chosen = switch (policy) {
            case "eager" -> ControlPolicy.EAGER;
            case "random" -> ControlPolicy.RANDOM;
            case "goal" -> ControlPolicy.GOAL;
            default -> throw usage("--policy must be eager, random or goal: " + policy);
        };
        Network network = ModelLoader.load(model);
        TestInterface testInterface = CommandModel.interfaceOf(network, interfaceFile);
        if (testInterface.inputs().isEmpty()) {
            err.println("dtron control: " + model + " has no commands: name the controller's channels i_x, or give"
                    + " --interface FILE.trn");
            return 1;
        }
        long unit = timeUnit != null ? timeUnit : testInterface.timeUnitMicros() != null
                ? testInterface.timeUnitMicros() : RunDefaults.timeUnit();
        if (unit <= 0) {
            throw usage("--timeunit must be a positive number of microseconds: " + unit);
        }
        if (!TestOptions.fits(duration, unit)) {
            throw usage(TestOptions.tooLong("--duration", duration, unit));
        }
        long runSeed = RunDefaults.seed(seed);
        TestOptions options = TestOptions.defaults(runSeed).withTimeUnit(unit).withTimeout(duration)
                .withVirtualTime(virtualTime);
        if (onBus) {
            return controlOnBus(network, testInterface, options, chosen, out, err);
        }
        Network plantModel = network;
        String plantName = "the model's own plant part";
        if (plantMutant != null) {
            Mutant mutant = mutant(network, testInterface, plantMutant);
            plantModel = mutant.network();
            plantName = "mutant " + mutant.number() + " of the plant part (" + mutant.kind().label() + ": "
                    + mutant.change() + ")";
        }
        ModelSystem plantSystem = new ModelSystem(plantModel, testInterface,
                plantSeed != null ? plantSeed : ModelSystem.seedFor(runSeed));
        Controller controller = controller(network, testInterface, plantSystem, options, chosen);
        out.println("dtron control: " + model + " against " + plantName + ", policy " + policy + ", " + duration
                + " time units in virtual time, seed " + runSeed);
        out.flush();
        return run(controller, testInterface, unit, plantName, out, err);
    }

    /**
     * Control of a plant on the bus, in real time: the run's owner on the bus ({@link io.dtron.bridge.BusRun}, through
     * its {@link BusBridge}, the controller's plant) waits for the plant and prepares the run; the controller runs it.
     */
    private int controlOnBus(Network network, TestInterface testInterface, TestOptions options, ControlPolicy chosen,
            PrintWriter out, PrintWriter err) throws ModelException {
        long unit = options.timeUnitMicros();
        String where = "bus '" + clusterName() + "' at " + (nats.given() ? String.join(",", nats.servers(this::usage))
                : "127.0.0.1");
        Supplier<DtronOptions.Builder> transport = nats.given() ? nats.memberOptions(clusterName(), this::usage)
                : () -> DtronOptions.builder().clusterName(clusterName())
                        .bindAddress(java.net.InetAddress.getLoopbackAddress());
        DtronOptions.Builder busOptions = secret.apply(transport.get());
        BusBridge bridge;
        try {
            bridge = BusBridge.connect(testInterface, busOptions);
        } catch (IllegalArgumentException e) {
            err.println("dtron control: " + model + ": " + e.getMessage());
            return 1;
        } catch (DtronException e) {
            err.println("dtron control: " + e.getMessage() + (e.getCause() == null ? "" : ": "
                    + e.getCause().getMessage()));
            return 1;
        }
        try (bridge) {
            // the controller's thread wakes up late on a busy machine: commands are aimed that far inside their windows
            SchedulingDelay lateness = SchedulingDelay.measureWarmingUp(network, testInterface);
            lateness.narrowInputWindow(network, testInterface, unit, "--plant model --virtual-time", channel -> 0,
                    channel -> false)
                    .ifPresent(warning -> err.println("dtron control: warning: " + warning.replace("(INCONCLUSIVE,"
                            + " input executed too late)", "(the controller then stops: the command's window had"
                            + " closed)")));
            err.flush();
            long margin = lateness.marginMicros();
            Controller controller = controller(network, testInterface, bridge, options.withInputMargin(margin),
                    chosen);
            long seconds = waitTimeout == null ? 30 : waitTimeout;
            out.println("dtron control: " + model + " against the plant on " + where + " as " + bridge.run().memberId()
                    + ", policy " + policy + ", " + duration + " time units of " + unit + " us in real time, seed "
                    + options.seed());
            out.println("dtron control: waiting up to " + seconds + " s for the plant to serve every command and"
                    + " reading");
            out.flush();
            Optional<String> refused;
            try {
                refused = new BusRunSequence(bridge.run()).prepareForControl(Duration.ofSeconds(seconds));
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                err.println("dtron control: interrupted while waiting for the plant");
                return 1;
            }
            if (refused.isPresent()) {
                err.println("dtron control: " + where + ": " + refused.get());
                return 1;
            }
            int exit;
            try (ModelVersionBus versions = reloadFromBus ? new ModelVersionBus(bridge.run().member(), controller,
                    model, interfaceFile, testInterface, unit) : null) {
                if (versions != null) {
                    versions.listen();
                }
                out.println("dtron control: every command and reading is served"
                        + BusRunLines.servedSummary(bridge.run()) + (versions == null ? "" : "; model versions are"
                        + " taken from the bus"));
                out.flush();
                exit = run(controller, testInterface, unit, "the plant on " + where, out, err);
            }
            BusSession.printSummary(bridge.run(), "controller", out);
            BusTiming.runDelays(bridge.run()).ifPresent(out::println);
            return exit;
        }
    }

    /** A controller of {@code plant} with the policy and the safe action of the options. */
    private Controller controller(Network network, TestInterface testInterface, Adapter plant, TestOptions options,
            ControlPolicy chosen) {
        Controller controller = new Controller(network, testInterface, plant, options);
        try {
            controller.policy(chosen, goals);
            controller.safeAction(safeAction != null ? SafeAction.channel(safeAction)
                    : safeLocation != null ? SafeAction.location(safeLocation) : SafeAction.NONE);
        } catch (IllegalArgumentException e) {
            throw usage(e.getMessage());
        }
        return controller;
    }

    /**
     * Runs the controller of {@code plantName}, with the file of new versions watched, prints its end and writes
     * {@code --junit}.
     */
    private int run(Controller controller, TestInterface testInterface, long unit, String plantName, PrintWriter out,
            PrintWriter err) throws ModelException {
        Printer printer = new Printer(out, unit);
        controller.addListener(printer);
        ModelVersionFile versions = reloadFrom == null ? null : new ModelVersionFile(reloadFrom, model, interfaceFile,
                testInterface, new ModelVersionFile.Sink() {
                    @Override
                    public void checked(ModelVersion.Check check) {
                        controller.offer(check);
                    }

                    @Override
                    public void unloadable(String version, String reason) {
                        controller.refuse(version, reason);
                    }
                });
        if (reloadFrom != null && !Files.exists(reloadFrom)) {
            out.println("dtron control: --reload-from " + reloadFrom + ": no such file yet; a version written there"
                    + " is checked when it appears");
        }
        ControlResult result;
        long began = System.nanoTime();
        ScheduledExecutorService progress = Progress.every(() -> printer.progress(began));
        try {
            if (versions != null) {
                versions.checkNow();
                versions.watch();
            }
            result = controller.run();
        } finally {
            Progress.stop(progress);
            if (versions != null) {
                versions.close();
            }
        }
        if (result.outcome() == ControlResult.Outcome.STOPPED) {
            out.println("stopped: " + result.reason());
        } else if (result.outcome() == ControlResult.Outcome.ALARM && result.safeAction() == null) {
            out.println("no safe action (--safe-action, --safe-location): the controller stopped");
        }
        out.println(result.summary(unit));
        if (junit != null && !report(result, unit, plantName, (System.nanoTime() - began) / 1e9, err)) {
            return 1;
        }
        return switch (result.outcome()) {
            case COMPLETED -> 0;
            case ALARM -> 2;
            case STOPPED -> 3;
        };
    }

    /**
     * {@code --junit}: the run as one test case, an alarm a failure, a run stopped for another reason an error;
     * returns false, having said why, if the file could not be written.
     */
    private boolean report(ControlResult result, long unit, String plantName, double seconds, PrintWriter err) {
        String name = "control against " + plantName + ", seed " + result.seed();
        JunitXml.Case run = switch (result.outcome()) {
            case COMPLETED -> new JunitXml.Case(name, null, null, "completed");
            case ALARM -> new JunitXml.Case(name, "failure", "ALARM", "ALARM at " + ControlResult.time(
                    result.alarmMicros(), unit) + ": " + result.reason() + (result.safeAction() == null
                    ? "; no safe action" : "; safe action " + result.safeAction() + " taken"));
            case STOPPED -> new JunitXml.Case(name, "error", "STOPPED", result.reason());
        };
        Map<String, String> p = new LinkedHashMap<>();
        p.put("model", model.toString());
        p.put("plant", plantName);
        p.put("policy", policy);
        p.put("seed", Long.toString(result.seed()));
        p.put("duration", Long.toString(duration));
        p.put("timeunit_us", Long.toString(unit));
        p.put("virtual_time", Boolean.toString(virtualTime));
        p.put("outcome", result.outcome().name());
        p.put("commands", Integer.toString(result.commands()));
        p.put("readings", Integer.toString(result.readings()));
        p.put("alarms", Integer.toString(result.alarms()));
        if (result.safeAction() != null) {
            p.put("safe_action", result.safeAction());
        }
        p.put("versions_taken", String.join("; ", result.versions()));
        p.put("versions_refused", String.join("; ", result.refused()));
        return JunitXml.writeOrSay(junit, "control", model, List.of(run), p, seconds, result.summary(unit), err);
    }

    private Mutant mutant(Network network, TestInterface testInterface, int number) {
        List<Mutant> mutants = Mutants.derive(network, testInterface, Duration.ofSeconds(10));
        if (number < 1 || number > mutants.size()) {
            throw usage("--plant-mutant " + number + ": the plant part has mutants 1 to " + mutants.size()
                    + " (dtron mutants " + model + " lists them)");
        }
        Mutant mutant = mutants.get(number - 1);
        if (mutant.invalid() != null) {
            throw usage("--plant-mutant " + number + " cannot be run: " + mutant.invalid());
        }
        return mutant;
    }

    /** The bus's name: {@code --cluster}, or the default. */
    private String clusterName() {
        return cluster != null ? cluster : DtronOptions.DEFAULT_CLUSTER;
    }

    private ParameterException usage(String message) {
        return new ParameterException(spec.commandLine(), message);
    }

    /**
     * Prints the alarms, the safe action and the model versions as they come, and a progress line when asked (every
     * {@link Progress#EVERY}, whether or not anything happens): the commands and readings so far and the time of the
     * last.
     */
    private static final class Printer implements ControlListener {
        private final PrintWriter out;
        private final long unit;
        private final AtomicInteger commands = new AtomicInteger();
        private final AtomicInteger readings = new AtomicInteger();
        private volatile long lastMicros = -1;

        Printer(PrintWriter out, long unit) {
            this.out = out;
            this.unit = unit;
        }

        @Override
        public void commandSent(Event command, long micros) {
            commands.incrementAndGet();
            lastMicros = micros;
        }

        @Override
        public void readingTaken(Event reading, long micros) {
            readings.incrementAndGet();
            lastMicros = micros;
        }

        /** The progress line of a run that began at {@code beganNanos}. */
        void progress(long beganNanos) {
            int c = commands.get();
            int r = readings.get();
            long last = lastMicros;
            print(String.format(Locale.ROOT, "progress: %.0f s elapsed, ", (System.nanoTime() - beganNanos) / 1e9) + c
                    + (c == 1 ? " command" : " commands") + " sent, " + r + (r == 1 ? " reading" : " readings")
                    + (last < 0 ? "" : ", the last at " + ControlResult.time(last, unit)));
        }

        @Override
        public void alarm(String reason, long micros) {
            print("ALARM at " + ControlResult.time(micros, unit) + ": " + reason);
        }

        @Override
        public void safeActionTaken(Event command, long micros) {
            commandSent(command, micros); // counted among the commands, as the summary counts it
            print("safe action " + command + " sent at " + ControlResult.time(micros, unit));
        }

        @Override
        public void versionTaken(String version, long micros) {
            print("model version " + version + " taken at " + ControlResult.time(micros, unit) + " (a reset point)");
        }

        @Override
        public void versionRefused(String version, String reason) {
            print("model version " + version + " refused: " + reason + "; the run goes on with the one it has");
        }

        private void print(String line) {
            synchronized (out) {
                out.println(line);
                out.flush();
            }
        }
    }
}
