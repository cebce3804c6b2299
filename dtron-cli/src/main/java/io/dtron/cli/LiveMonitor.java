package io.dtron.cli;

import static io.dtron.cli.MonitorCommand.events;
import static io.dtron.cli.MonitorCommand.violations;

import io.dtron.api.DtronException;
import io.dtron.api.DtronOptions;
import io.dtron.bridge.BusMonitor;
import io.dtron.bridge.BusRun;
import io.dtron.engine.JsonString;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.monitor.Alarm;
import io.dtron.engine.monitor.Monitor;
import io.dtron.engine.verify.QueryException;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.UncheckedIOException;
import java.io.Writer;
import java.net.InetAddress;
import java.net.UnknownHostException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.ScheduledExecutorService;
import java.util.function.Function;
import java.util.function.Supplier;
import java.util.function.ToIntBiFunction;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;

/**
 * The bus options of {@code dtron monitor} ({@code --cluster}, {@code --bus} and the transport's and security options
 * of {@code dtron run}, {@code --delta}, {@code --duration}, {@code --runs}, {@code --shield}) and the live watch: a
 * {@link BusMonitor} on the bus, its alarms printed as they come, each run's counts at its end and the runs' at the
 * end.
 */
final class LiveMonitor {
    /** The summary lists each run's violations up to this many runs; beyond, the runs with violations. */
    private static final int LISTED_RUNS = 10;

    @Option(names = "--cluster", paramLabel = "NAME",
            description = "Watch the bus of this name (default '" + DtronOptions.DEFAULT_CLUSTER + "' with --bus): the"
                    + " embedded JGroups bus, or the NATS bus of --bus.")
    private String cluster;

    @Option(names = "--bind", paramLabel = "ADDR",
            description = "On a JGroups bus: the network interface to bind to and to find members at (default:"
                    + " loopback).")
    private String bind;

    @Mixin
    private BusSecretOptions.OrInsecure secret;

    @Mixin
    private NatsBusOptions nats;

    /**
     * The automatic reorder window's start: four times the tester's floor. The tester measures the bus's delays
     * before its run and takes three times the longest (in a loaded CI run 67 ms, so 201 ms); the monitor, which does
     * not probe before a run, starts where such a window would, and a message that comes later than its window costs
     * the run's judgement (every reachable state from there, the run incomplete), while a wider window only delays
     * the monitor's alarms. It still widens when a message takes more than half of it.
     */
    static final long AUTO_WINDOW_MICROS = 4 * BusRun.AUTO_WINDOW_FLOOR_MICROS;

    @Option(names = "--delta", paramLabel = "US|auto",
            description = "On a bus: the reorder window, how long the monitor holds its judgement for messages still in"
                    + " transit (auto, the default: " + AUTO_WINDOW_MICROS + " us, widened when a message"
                    + " takes more than half of it).")
    private String delta;

    @Option(names = "--duration", paramLabel = "SECONDS",
            description = "On a bus: watch at most this long (default: until the last run of --runs ends).")
    private Long duration;

    @Option(names = "--runs", paramLabel = "N",
            description = "On a bus: follow N runs, one after another, and end after the last (default: 1); 0: every"
                    + " run, until --duration or an interrupt.")
    private Integer runs;

    @Option(names = "--shield", paramLabel = "CHANNEL[=SHIELDED]",
            description = "On a bus: shield CHANNEL: republish each of its messages the model allows on SHIELDED (default"
                    + " CHANNEL_shielded), where its consumers listen, and withhold the others (said in the alarm);"
                    + " goes on after violations (--continue).")
    private String shield;

    /** What the monitor starts from, and the options the replay shares. */
    record Start(Path model, Long timeUnit, String from, long toleranceMicros, boolean keepGoing, Path alarmsFile,
            Path junitFile) {
    }

    /** Whether a bus was given: the monitor watches it. */
    boolean onBus() {
        return cluster != null || nats.given();
    }

    /** Checks the options of a watch on the bus. */
    void check(Function<String, ParameterException> usage) {
        if (cluster != null && cluster.isBlank()) {
            throw usage.apply("--cluster: the bus name is blank");
        }
        secret.check(usage);
        if (duration != null && (duration <= 0 || duration > RunDefaults.MAX_WAIT_SECONDS)) {
            throw usage.apply("--duration must be a positive number of seconds: " + duration);
        }
        if (runs != null && runs < 0) {
            throw usage.apply("--runs must be a number of runs, at least 0 (0: every run): " + runs);
        }
        windowMicros(usage);
        if (shield != null && shieldChannels()[0].isBlank()) {
            throw usage.apply("--shield names a channel of the model: '" + shield + "'");
        }
        if (bind != null && nats.given()) {
            throw usage.apply("--bind is for a JGroups bus; a NATS bus is where --bus says");
        }
        nats.check(clusterName(), usage);
    }

    /** Checks that no option of a watch on the bus came with {@code --replay}. */
    void checkReplay(Function<String, ParameterException> usage) {
        if (bind != null || secret.given() || delta != null || duration != null || runs != null
                || shield != null) {
            throw usage.apply("--bind, --key-file, --insecure, --delta, --duration, --runs and --shield are for"
                    + " watching a bus (--cluster, --bus), not for --replay");
        }
        nats.check(clusterName(), usage);
    }

    /**
     * Watches the bus until the last run of {@code --runs} ends (or {@code --duration} passes, or the process is
     * interrupted), printing the alarms as they come and each run's counts at its end; returns the exit code.
     */
    int watch(Network network, TestInterface testInterface, Start start, PrintWriter out, PrintWriter err,
            Function<String, ParameterException> usage) {
        long unit = RunDefaults.timeUnit(start.timeUnit(), testInterface.timeUnitMicros());
        // a shield goes on after violations: it withholds what the model forbids for as long as it runs
        boolean keepGoing = start.keepGoing() || shield != null;
        String joinFrom = start.from() == null ? "any" : start.from();
        String runFrom = start.from() == null ? "initial" : start.from();
        Monitor first;
        try {
            // the model's errors and a bad --from come out here, whatever the start
            first = Monitor.of(network, testInterface, MonitorCommand.options(unit, runFrom, keepGoing));
            if (!joinFrom.equals(runFrom)) {
                first = Monitor.of(network, testInterface, MonitorCommand.options(unit, joinFrom, keepGoing));
            }
        } catch (QueryException e) {
            throw usage.apply("--from: " + e.getMessage());
        } catch (UnsupportedModelException e) {
            if (start.from() != null) {
                err.println("dtron monitor: " + start.model() + ": " + e.getMessage());
                return 1;
            }
            // too many states to start from all of them: the monitor watches from the next run start
            err.println("dtron monitor: " + start.model() + ": " + e.getMessage() + "; this monitor starts at the"
                    + " next run start, and cannot join a run already going (give --from PROPERTY for that)");
            first = null;
        }
        String[] shielded = shield == null ? new String[] {null, null} : shieldChannels();
        long window = windowMicros(usage);
        int watched = runs == null ? 1 : runs;
        BusMonitor.Settings settings = new BusMonitor.Settings(window, delta == null || delta.equals("auto"),
                start.toleranceMicros(), shielded[0], shielded[1], watched);
        Writer alarms;
        try {
            alarms = start.alarmsFile() == null ? Writer.nullWriter()
                    : Files.newBufferedWriter(start.alarmsFile(), StandardCharsets.UTF_8);
        } catch (IOException e) {
            err.println("dtron monitor: cannot write " + start.alarmsFile() + ": " + OutputFile.reason(e));
            return 1;
        }
        Printer printer = new Printer(out, alarms, unit, shielded[1], shield != null);
        Monitor joining = first;
        BusMonitor.Monitors monitors = runUnit -> runUnit == 0 ? joining : Monitor.of(network, testInterface,
                MonitorCommand.options(start.timeUnit() != null ? start.timeUnit() : runUnit, runFrom,
                        keepGoing));
        BusMonitor monitor;
        try {
            monitor = BusMonitor.connect(testInterface, monitors, settings, busOptions(usage).get(), printer);
        } catch (IllegalArgumentException e) {
            err.println("dtron monitor: " + start.model() + ": " + e.getMessage());
            return 1;
        } catch (DtronException e) {
            err.println("dtron monitor: " + e.getMessage() + (e.getCause() == null ? "" : ": "
                    + e.getCause().getMessage()));
            return 1;
        }
        printer.line("dtron monitor: " + start.model() + " on bus '" + clusterName() + "' at " + where(usage) + " as "
                + monitor.memberId() + ", from " + (joining == null ? MonitorCommand.start(runFrom) + " at each run start"
                : MonitorCommand.start(joinFrom) + (start.from() == null ? " (it joins a running system), from "
                + MonitorCommand.start(runFrom) + " at each run start" : ""))
                + ", time units of " + unit + " us (a run's own at its start), reorder window " + (settings
                .automaticWindow() ? "auto from " : "") + window + " us" + (start.toleranceMicros() > 0
                ? ", event times give or take " + start.toleranceMicros() + " us" : "") + (keepGoing
                ? ", going on after violations" : "") + (shield == null ? "" : ", shielding " + shielded[0] + " on "
                + shielded[1]) + (watched == 1 ? "" : watched == 0 ? ", following every run"
                : ", following " + watched + " runs"));
        long began = System.nanoTime();
        printer.runBegan = began;
        ScheduledExecutorService progress = Progress.every(() -> printer.progress(began, monitor.progress()));
        // the end of the watch: no progress line after the summary, the alarms' file closed, JUnit, the summary
        Ending ending = new Ending((result, interrupted) -> {
            Progress.stop(progress);
            try {
                alarms.close();
            } catch (IOException e) {
                err.println("dtron monitor: cannot write " + start.alarmsFile() + ": " + OutputFile.reason(e));
            }
            String summary = summary(result, shield != null, interrupted);
            if (start.junitFile() != null && !JunitXml.writeOrSay(start.junitFile(), "monitor", start.model(),
                    printer.cases(result.error()), properties(start, result, joinFrom, runFrom, window),
                    (System.nanoTime() - began) / 1e9, result.error() == null ? summary : result.error(), err)) {
                return 1;
            }
            if (result.error() != null) {
                err.println("dtron monitor: " + start.model() + ": " + result.error());
                return 1;
            }
            printer.line(summary);
            return result.violations() > 0 ? 2 : result.late() > 0 ? 3 : 0;
        });
        // an interrupt (SIGINT, SIGTERM) ends the watch as --duration would: the summary and the reports, once
        Thread hook = new Thread(() -> {
            ending.interrupted = true;
            try (monitor) {
                ending.end(monitor.finish());
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }, "dtron-monitor-end");
        Runtime.getRuntime().addShutdownHook(hook);
        try (monitor) {
            BusMonitor.Result result = duration == null
                    ? monitor.await(Duration.ofSeconds(RunDefaults.MAX_WAIT_SECONDS))
                    : monitor.await(Duration.ofSeconds(duration));
            return ending.end(result == null ? monitor.finish() : result);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            err.println("dtron monitor: interrupted");
            return 1;
        } finally {
            Progress.stop(progress);
            try {
                Runtime.getRuntime().removeShutdownHook(hook);
            } catch (IllegalStateException e) {
                // the JVM is going down: the hook ends the watch
            }
        }
    }

    /**
     * The end of a watch, done once whoever comes first (the watch's end, or the shutdown hook of an interrupt): the
     * report of the result, whether the watch was interrupted, gives the exit code.
     */
    private static final class Ending {
        private final ToIntBiFunction<BusMonitor.Result, Boolean> report;
        /** Set by the shutdown hook before it ends the watch: the summary says that the watch was interrupted. */
        volatile boolean interrupted;
        /** The exit code once the watch's end was reported; null before. */
        private Integer exit;

        Ending(ToIntBiFunction<BusMonitor.Result, Boolean> report) {
            this.report = report;
        }

        /** Reports the watch's {@code result} (the first call; later ones wait for it) and returns the exit code. */
        synchronized int end(BusMonitor.Result result) {
            if (exit == null) {
                exit = report.applyAsInt(result, interrupted);
            }
            return exit;
        }
    }

    /** The properties of {@code --junit}: the watch's settings and the counts of all its runs. */
    private Map<String, String> properties(Start start, BusMonitor.Result result, String joinFrom, String runFrom,
            long window) {
        Map<String, String> p = new LinkedHashMap<>();
        p.put("model", start.model().toString());
        p.put("bus", clusterName());
        p.put("from_joining", joinFrom);
        p.put("from_run_start", runFrom);
        p.put("reorder_window", (delta == null || delta.equals("auto") ? "auto from " : "") + window + " us");
        p.put("tolerance_us", Long.toString(start.toleranceMicros()));
        if (shield != null) {
            p.put("shield", shieldChannels()[0] + " on " + shieldChannels()[1]);
            p.put("withheld", Long.toString(result.withheld()));
        }
        p.put("runs", Integer.toString(result.runs().size()));
        p.put("events", Long.toString(result.events()));
        p.put("violations", Integer.toString(result.violations()));
        p.put("too_late", Long.toString(result.late()));
        return p;
    }

    /**
     * The line at the end: the runs, the violations of all and of each (of more than ten runs, those with violations,
     * the others counted), the events, the messages too late to judge, of a shield those withheld, and the events
     * after their runs' ends if any.
     */
    static String summary(BusMonitor.Result result, boolean shield, boolean interrupted) {
        int n = result.runs().size();
        List<String> perRun = new ArrayList<>();
        long clean = result.runs().stream().filter(r -> r.violations() == 0).count();
        if (n > LISTED_RUNS && clean > 0) {
            perRun.add(clean + " run" + (clean == 1 ? "" : "s") + " without violations");
        }
        result.runs().stream().filter(r -> n <= LISTED_RUNS || r.violations() > 0)
                .forEach(r -> perRun.add(Printer.name(r) + ": " + r.violations()));
        return "dtron monitor: " + (interrupted ? "interrupted, " : "") + n + " run" + (n == 1 ? "" : "s") + ", "
                + violations(result.violations()) + " ("
                + String.join(", ", perRun) + "), " + events(result.events()) + ", " + result.late()
                + " too late to judge" + (shield ? ", " + result.withheld() + " withheld" : "")
                + afterTheEnd(result.afterEnd());
    }

    /** ", N after the run's end" when events came stamped after their run's end (not judged); else "". */
    private static String afterTheEnd(long n) {
        return n == 0 ? "" : ", " + n + " after the run's end (not judged)";
    }

    /** The reorder window: {@code --delta US}, or the automatic one's start. */
    private long windowMicros(Function<String, ParameterException> usage) {
        if (delta == null || delta.equals("auto")) {
            return AUTO_WINDOW_MICROS;
        }
        try {
            long micros = Long.parseLong(delta);
            if (micros >= 0) {
                return micros;
            }
        } catch (NumberFormatException e) {
            // said below
        }
        throw usage.apply("--delta must be auto or a number of microseconds, at least 0: " + delta);
    }

    /** {@code --shield CHANNEL[=SHIELDED]}: the channel and where its allowed messages go. */
    private String[] shieldChannels() {
        int eq = shield.indexOf('=');
        String channel = (eq < 0 ? shield : shield.substring(0, eq)).trim();
        String shielded = eq < 0 ? channel + "_shielded" : shield.substring(eq + 1).trim();
        return new String[] {channel, shielded};
    }

    private String clusterName() {
        return cluster != null ? cluster : DtronOptions.DEFAULT_CLUSTER;
    }

    private String where(Function<String, ParameterException> usage) {
        return nats.given() ? String.join(",", nats.servers(usage)) : bindAddress(usage).getHostAddress();
    }

    private InetAddress bindAddress(Function<String, ParameterException> usage) {
        if (bind == null) {
            return InetAddress.getLoopbackAddress();
        }
        try {
            return InetAddress.getByName(bind);
        } catch (UnknownHostException e) {
            throw usage.apply("--bind: unknown address '" + bind + "'");
        }
    }

    /** The member's options: the transport's, with the bus's secret of {@code --key-file} or none. */
    private Supplier<DtronOptions.Builder> busOptions(Function<String, ParameterException> usage) {
        Supplier<DtronOptions.Builder> transport = nats.given() ? nats.memberOptions(clusterName(), usage)
                : () -> DtronOptions.builder().clusterName(clusterName()).bindAddress(bindAddress(usage));
        return () -> secret.apply(transport.get());
    }

    /** Prints what the monitor finds, from its thread, and writes the alarms' and notes' JSON lines. */
    private static final class Printer implements BusMonitor.Sink {
        private final PrintWriter out;
        private final Writer alarms;
        private final String shielded;
        private final boolean shielding;
        private volatile long unit;
        /** For --junit: the cases of the runs ended. */
        private final List<JunitXml.Case> cases = new ArrayList<>();
        /**
         * When the run watched began ({@link System#nanoTime}): its start, else the last run's end or the watch's
         * beginning; each run's case takes its own time.
         */
        private volatile long runBegan = System.nanoTime();

        Printer(PrintWriter out, Writer alarms, long unit, String shielded, boolean shielding) {
            this.out = out;
            this.alarms = alarms;
            this.unit = unit;
            this.shielded = shielded;
            this.shielding = shielding;
        }

        /** What to call a run: its id, or the watch of a system that named none. */
        static String name(BusMonitor.RunResult run) {
            return run.runId().isEmpty() ? "the watch" : "run " + run.runId();
        }

        @Override
        public void runEnded(BusMonitor.RunResult run) {
            synchronized (cases) {
                String missing = run.late() == 0 ? null
                        : run.late() + (run.late() == 1 ? " message" : " messages") + " came too late to judge";
                long now = System.nanoTime();
                cases.add(MonitorCommand.junitCase(name(run), run.violations(), run.firstAlarm(), unit, missing)
                        .took((now - runBegan) / 1e9));
                runBegan = now; // what comes before the next run's start is the next case's
            }
            line(name(run) + " ended: " + violations(run.violations()) + ", " + events(run.events()) + switch (run
                    .end()) {
                case STOPPED -> " (the run ended)";
                case FIRST_VIOLATION -> " (stopped at the first violation)";
                case NEXT_RUN -> " (the next run started before its end)";
                case WATCH_ENDED -> "";
                case GAVE_UP -> " (the monitor could not follow it to its end)";
            } + ", " + run.late() + " too late to judge" + (shielding ? ", " + run.withheld() + " withheld" : "")
                    + afterTheEnd(run.afterEnd()) + "; verdict published on dtron_alarm");
        }

        @Override
        public void runStarted(String runId, long timeUnitMicros) {
            runBegan = System.nanoTime();
            unit = timeUnitMicros;
            line("run " + runId + " started (time units of " + timeUnitMicros + " us): the monitor starts again");
        }

        @Override
        public void alarm(Alarm alarm, boolean withheld) {
            write(alarm.toJson());
            synchronized (out) {
                MonitorCommand.print(out, alarm, unit, withheld ? "; withheld: not republished on " + shielded : "");
                out.flush();
            }
        }

        /**
         * The progress line of a watch that began at {@code beganNanos} (every {@link Progress#EVERY}, whether or not
         * anything happens): the time watching, the run watched and the time up to which it was judged, its counts,
         * and the runs ended before it.
         */
        void progress(long beganNanos, BusMonitor.Progress p) {
            StringBuilder line = new StringBuilder(String.format(Locale.ROOT, "progress: %.0f s watching",
                    (System.nanoTime() - beganNanos) / 1e9));
            if (p.watching()) {
                line.append(", ").append(p.runId().isEmpty() ? "the watch" : "run " + p.runId());
                if (p.judgedToMicros() >= 0) {
                    line.append(" judged to t=").append(MonitorCommand.units(p.judgedToMicros(), unit));
                }
                line.append(", ").append(events(p.events())).append(", ").append(violations(p.violations()))
                        .append(", ").append(p.late()).append(" too late to judge");
                if (shielding) {
                    line.append(", ").append(p.withheld()).append(" withheld");
                }
            } else {
                line.append(", waiting for a run's start");
            }
            if (p.runsEnded() > 0) {
                line.append(", ").append(p.runsEnded()).append(p.runsEnded() == 1 ? " run" : " runs").append(" ended");
            }
            line(line.toString());
        }

        /**
         * The test cases of the runs watched, for {@code --junit}; with an {@code error} that stopped the watch, one
         * more, an error with it.
         */
        List<JunitXml.Case> cases(String error) {
            synchronized (cases) {
                List<JunitXml.Case> all = new ArrayList<>(cases);
                if (error != null) {
                    all.add(new JunitXml.Case("the watch", "error", "ERROR", error));
                }
                return all;
            }
        }

        /** A note is printed, and written among the alarms as {@code {"kind":"note","text":...}}. */
        @Override
        public void note(String line) {
            write("{\"kind\":\"note\",\"text\":" + JsonString.quote(line) + "}");
            line("dtron monitor: " + line);
        }

        /** Writes a line of JSON to the alarms' file. */
        private void write(String json) {
            try {
                alarms.write(json);
                alarms.write('\n');
                alarms.flush();
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
        }

        void line(String line) {
            synchronized (out) {
                out.println(line);
                out.flush();
            }
        }
    }
}
