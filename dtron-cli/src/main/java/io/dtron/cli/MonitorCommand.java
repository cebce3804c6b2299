package io.dtron.cli;

import io.dtron.engine.Event;
import io.dtron.engine.TestOptions;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.monitor.Alarm;
import io.dtron.engine.monitor.Monitor;
import io.dtron.engine.monitor.MonitorOptions;
import io.dtron.engine.verify.QueryException;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.Writer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.OptionalLong;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron monitor MODEL --replay TRACE}: runtime verification of a recorded run. Every event of the trace, on
 * any observable channel of the closed model, is checked against the model with its time, and a missed deadline
 * is found at its time; prints the first violation (or each, with {@code --continue}) and the counts. With {@code
 * --cluster NAME} or {@code --bus nats://...} instead, the same live on a bus ({@link LiveMonitor}).
 */
@Command(name = "monitor", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Runtime verification: check a recorded run (--replay), or a running system on a bus"
                + " (--cluster NAME, --bus nats://HOST:PORT), against a closed model.",
                "Every event of TRACE (inputs and outputs alike) is checked with its time against the states the model"
                        + " can be in; a deadline the model sets is found when time passes it. TRACE is JSON lines"
                        + " (dtron run --trace, or lines {\"t_us\":..,\"channel\":..,\"values\":{..}}) or, for a name"
                        + " ending in .csv, lines t_us,channel,name=value;name=value. A line that cannot be read is"
                        + " reported and counted, and the monitor starts again from every reachable state after it.",
                "On a bus the monitor observes every channel of the model as a passive member, orders the events by"
                        + " their times within the reorder window, finds missed deadlines as the run's clock passes"
                        + " them, and publishes its alarms and verdict on the reserved channel dtron_alarm; --shield"
                        + " CHANNEL republishes the messages of CHANNEL the model allows and withholds the others.",
                "Exit code 0 no violation, 2 a violation, 3 no violation but lines were rejected (on a bus: messages"
                        + " came too late to be judged), 1 usage or model error."})
final class MonitorCommand implements Callable<Integer> {
    /** With --continue, the violations printed in full; the others are counted. */
    private static final int PRINTED = 10;

    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The closed model (.xml, .xta, or an Uppaal 3 .ta).")
    private Path model;

    @Option(names = "--interface", paramLabel = "FILE.trn",
            description = "Take the observable channels from a TRON interface file instead of the i_/o_ names.")
    private Path interfaceFile;

    @Option(names = "--replay", paramLabel = "TRACE",
            description = "The recorded run to check (or watch a bus: --cluster, --bus).")
    private Path replay;

    @Mixin
    private LiveMonitor live;

    @Option(names = "--timeunit", paramLabel = "US",
            description = "Microseconds per model time unit (default: the trace's, or on a bus the run's, else the"
                    + " interface file's precision, else 1000).")
    private Long timeUnit;

    @Option(names = "--from", paramLabel = "STATE",
            description = "Where the model starts: initial (its initial state at time 0, the default of --replay),"
                    + " any (every state it can reach, at the first event: the history is unknown), or a state"
                    + " property such as 'Lamp.off' or 'Server.Busy && n == 3' (the reachable states where it holds)."
                    + " On a bus the default is any when the monitor joins a running system, and initial at each run"
                    + " start it sees.")
    private String from;

    @Option(names = "--tolerance", paramLabel = "US", defaultValue = "0",
            description = "Take each event's time give or take US microseconds (the clock error of the recorder;"
                    + " default: 0).")
    private long toleranceMicros;

    @Option(names = "--end", paramLabel = "US",
            description = "With --replay: the run ended at US microseconds on its clock (a deadline before it is judged"
                    + " even without a later event; an event after it is rejected). Default: the trace's verdict line,"
                    + " else its last event; a deadline still pending there is reported as not judged.")
    private Long endOption;

    @Option(names = "--continue", description = "Go on after a violation: count them, and start again after each"
            + " from every reachable state consistent with the event.")
    private boolean keepGoing;

    @Option(names = "--alarms", paramLabel = "FILE", description = "Write every alarm as a line of JSON to FILE (live,"
            + " the monitor's notes too: messages too late to judge, a widened window, members silent before an"
            + " alarm).")
    private Path alarmsFile;

    @Option(names = "--junit", paramLabel = "FILE.xml", description = "Write what the monitor judged as a JUnit XML"
            + " report to FILE.xml: one test case for the replay, or per run watched on a bus; a violation a failure"
            + " with the first, rejected lines or messages too late to judge an error.")
    private Path junit;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        if (timeUnit != null && (timeUnit <= 0 || timeUnit > TestOptions.MAX_DURATION_MICROS)) {
            throw usage("--timeunit must be a positive number of microseconds, at most "
                    + TestOptions.MAX_DURATION_MICROS + ": " + timeUnit);
        }
        if (toleranceMicros < 0 || toleranceMicros > TestOptions.MAX_DURATION_MICROS) {
            throw usage("--tolerance must be 0 to " + TestOptions.MAX_DURATION_MICROS + " us (about 292 years): "
                    + toleranceMicros);
        }
        if (endOption != null && (endOption < 0 || endOption > TestOptions.MAX_DURATION_MICROS)) {
            throw usage("--end must be a time of the run, 0 to " + TestOptions.MAX_DURATION_MICROS + " us: "
                    + endOption);
        }
        if (endOption != null && replay == null) {
            throw usage("--end is the end of a replayed run (--replay); on a bus a run's end is the tester's");
        }
        if (replay == null && !live.onBus()) {
            throw usage("give the run to check: --replay TRACE, or the bus to watch: --cluster NAME or --bus"
                    + " nats://HOST:PORT");
        }
        if (replay != null && live.onBus()) {
            throw usage("--replay checks a recorded run; leave out --cluster and --bus, or --replay");
        }
        for (String problem : new String[] {OutputFile.problem("--junit", junit, model, replay, interfaceFile),
                OutputFile.problem("--alarms", alarmsFile, model, replay, interfaceFile, junit)}) {
            if (problem != null) {
                throw usage(problem);
            }
        }
        if (replay == null) {
            live.check(this::usage);
        } else {
            live.checkReplay(this::usage);
        }
        if (replay != null && OutputFile.unreadable(replay) != null) {
            err.println("dtron monitor: cannot read " + replay + ": " + OutputFile.unreadable(replay));
            return 1;
        }
        CommandModel.Loaded loaded = CommandModel.load("monitor", model, interfaceFile, err);
        if (loaded == null) {
            return 1;
        }
        Network network = loaded.network();
        TestInterface testInterface = loaded.testInterface();
        if (testInterface.inputs().isEmpty() && testInterface.outputs().isEmpty()) {
            err.println("dtron monitor: " + model + " has no observable channels: name channels i_x / o_y, or give"
                    + " --interface FILE.trn");
            return 1;
        }
        if (replay == null) {
            return live.watch(network, testInterface, new LiveMonitor.Start(model, timeUnit, from, toleranceMicros,
                    keepGoing, alarmsFile, junit), out, err, this::usage);
        }
        TraceReader.Format format = TraceReader.formatOf(replay);
        Monitor monitor;
        long unit;
        try {
            Long traceUnit;
            try {
                traceUnit = format == TraceReader.Format.JSON_LINES && timeUnit == null
                        ? TraceReader.timeUnit(replay) : null;
            } catch (IllegalArgumentException e) {
                err.println("dtron monitor: " + replay + ":1: " + e.getMessage() + ": give the time unit with"
                        + " --timeunit");
                return 1;
            }
            unit = RunDefaults.timeUnit(timeUnit, traceUnit, testInterface.timeUnitMicros());
            monitor = Monitor.of(network, testInterface, options(unit));
        } catch (IOException e) {
            err.println("dtron monitor: cannot read " + replay + ": " + OutputFile.reason(e));
            return 1;
        } catch (QueryException e) {
            throw usage("--from: " + e.getMessage());
        } catch (UnsupportedModelException e) {
            err.println("dtron monitor: " + model + ": " + e.getMessage());
            return 1;
        }
        out.println("dtron monitor: " + model + ", replay of " + replay + " (" + (format == TraceReader.Format.CSV
                ? "CSV" : "JSON lines") + "), from " + start() + ", time units of " + unit + " us"
                + (toleranceMicros > 0 ? ", event times give or take " + toleranceMicros + " us" : "")
                + (keepGoing ? ", going on after violations" : ""));
        Replay r = new Replay(monitor, out, err, unit);
        long began = System.nanoTime();
        try {
            r.alarms = alarmsFile == null ? Writer.nullWriter()
                    : Files.newBufferedWriter(alarmsFile, StandardCharsets.UTF_8);
        } catch (IOException e) {
            err.println("dtron monitor: cannot write the alarms to " + alarmsFile + ": " + OutputFile.reason(e));
            return 1;
        }
        try {
            TraceReader.read(replay, format, r);
            r.report(r.endMicros >= 0 ? monitor.advanceTo(r.endMicros) : null);
            r.unjudged = r.endKnown || endOption != null ? OptionalLong.empty() : monitor.pendingDeadline();
        } catch (IOException e) {
            err.println("dtron monitor: cannot read " + replay + ": " + OutputFile.reason(e));
            return 1;
        } catch (UnsupportedModelException e) {
            err.println("dtron monitor: " + model + ": " + e.getMessage());
            return 1;
        } finally {
            r.closeAlarms();
        }
        double seconds = (System.nanoTime() - began) / 1e9;
        int violations = monitor.violations();
        String unjudged = r.unjudged.isEmpty() ? null : "the deadline at t=" + units(r.unjudged.getAsLong(), unit)
                + " after the last event at t=" + units(monitor.lastMicros(), unit) + " was not judged: the trace"
                + " does not say when the run ended (give it with --end US)";
        if (unjudged != null) {
            out.println("dtron monitor: " + unjudged);
        }
        String summary = "dtron monitor: " + violations(violations) + ", " + events(monitor.events())
                + (monitor.gaveUp().isPresent() ? " (not followed to the end: " + monitor.gaveUp().get() + ")"
                        : monitor.stopped() ? " (stopped at the first violation)" : "") + ", " + rejected(r.rejected)
                + (unjudged == null ? "" : ", a deadline after the last event not judged")
                + ", in " + String.format(Locale.ROOT, "%.2f s", seconds);
        out.println(summary);
        if (junit != null && !replayReport(r, monitor, format, unit, seconds, summary, unjudged, err)) {
            return 1;
        }
        return violations > 0 ? 2 : r.rejected > 0 || monitor.gaveUp().isPresent() || unjudged != null ? 3 : 0;
    }

    /**
     * {@code --junit} of a replay: one test case ({@code unjudged}: the deadline not judged at the trace's end, or
     * null); returns false if the file could not be written.
     */
    private boolean replayReport(Replay r, Monitor monitor, TraceReader.Format format, long unit, double seconds,
            String summary, String unjudged, PrintWriter err) {
        String missing = r.rejected == 0 ? unjudged : r.rejected + " line" + (r.rejected == 1 ? "" : "s")
                + " of the trace rejected, the first " + r.firstRejected + (unjudged == null ? "" : "; " + unjudged);
        JunitXml.Case replayed = junitCase("replay of " + replay, monitor.violations(), monitor.firstAlarm(),
                unit, missing);
        Map<String, String> properties = new LinkedHashMap<>();
        properties.put("model", model.toString());
        properties.put("trace", replay.toString());
        properties.put("format", format == TraceReader.Format.CSV ? "csv" : "json-lines");
        properties.put("from", from == null ? "initial" : from);
        properties.put("timeunit_us", Long.toString(unit));
        properties.put("tolerance_us", Long.toString(toleranceMicros));
        properties.put("continue", Boolean.toString(keepGoing));
        properties.put("end", r.endKnown ? "the trace's" : endOption != null ? endOption + " us" : "its last event");
        properties.put("events", Long.toString(monitor.events()));
        properties.put("violations", Integer.toString(monitor.violations()));
        properties.put("rejected_lines", Integer.toString(r.rejected));
        return JunitXml.writeOrSay(junit, "monitor", model, List.of(replayed), properties, seconds, summary, err);
    }

    private MonitorOptions options(long unit) {
        return options(unit, from == null ? "initial" : from, keepGoing);
    }

    /** The monitor's options for a start named as {@code --from} names it. */
    static MonitorOptions options(long unit, String from, boolean keepGoing) {
        MonitorOptions o = switch (from) {
            case "initial" -> MonitorOptions.initial(unit);
            case "any" -> MonitorOptions.anyState(unit);
            default -> MonitorOptions.from(unit, from);
        };
        return o.keepGoing(keepGoing);
    }

    private String start() {
        return start(from == null ? "initial" : from);
    }

    /** The start {@code --from} names, in words. */
    static String start(String from) {
        return switch (from) {
            case "initial" -> "the initial state";
            case "any" -> "every reachable state";
            default -> "the reachable states where " + from + " holds";
        };
    }

    /** The replay: feeds the monitor, prints the alarms and the rejected lines. */
    private final class Replay implements TraceReader.Sink {
        private final Monitor monitor;
        private final PrintWriter out;
        private final PrintWriter err;
        private final long unit;
        private Writer alarms;
        private int rejected;
        private long endMicros = -1;
        private long lastMicros = -1;
        /** Whether the trace said where the run ended (a verdict line). */
        private boolean endKnown;
        /** The deadline pending at the last event of a trace whose end is not known; empty when none. */
        private OptionalLong unjudged = OptionalLong.empty();
        private final ReplayProgress progress;
        /** The first line rejected ("LINE: reason"), for --junit; null until one is. */
        private String firstRejected;

        Replay(Monitor monitor, PrintWriter out, PrintWriter err, long unit) {
            this.monitor = monitor;
            this.out = out;
            this.err = err;
            this.unit = unit;
            this.progress = new ReplayProgress(out, unit, Progress.EVERY);
            if (endOption != null) {
                this.endMicros = endOption;
            }
        }

        @Override
        public void event(Event event, long micros, int line) {
            if (endOption != null && micros > endOption) {
                rejected(line, "the event at " + micros + " us comes after the run's end at " + endOption
                        + " us (--end)");
                return;
            }
            Alarm a;
            try {
                a = monitor.observe(event, micros, toleranceMicros);
            } catch (IllegalArgumentException e) {
                rejected(line, e.getMessage());
                return;
            }
            lastMicros = Math.max(lastMicros, micros);
            this.endMicros = Math.max(this.endMicros, micros);
            report(a);
            progress.after(line, lastMicros, monitor, rejected);
        }

        @Override
        public void end(long micros, int line) {
            if (micros < lastMicros) {
                rejected(line, "the run ends at " + micros + " us, before its last event at " + lastMicros + " us");
                return;
            }
            endKnown = true;
            this.endMicros = endOption == null ? micros : Math.min(micros, endOption);
        }

        @Override
        public void rejected(int line, String why) {
            // a line of megabytes (a value, a channel name) is not echoed whole
            String reason = why.length() <= 300 ? why : why.substring(0, 300) + "... (" + why.length()
                    + " characters)";
            rejected++;
            if (firstRejected == null) {
                firstRejected = line + ": " + reason;
            }
            err.println(replay + ":" + line + ": " + reason);
            monitor.forgetHistory();
            progress.after(line, lastMicros, monitor, rejected);
        }

        void report(Alarm a) {
            if (a == null) {
                return;
            }
            try {
                alarms.write(a.toJson());
                alarms.write('\n');
            } catch (IOException e) {
                alarmsLost(e);
            }
            print(out, a, unit, "");
        }

        /** Closes the file of {@code --alarms}, saying if what it held could not be written. */
        void closeAlarms() {
            try {
                alarms.close();
            } catch (IOException e) {
                alarmsLost(e);
            }
        }

        /** The file of {@code --alarms} failed: said once, and the replay goes on without it. */
        private void alarmsLost(IOException e) {
            err.println("dtron monitor: cannot write the alarms to " + alarmsFile + ": " + OutputFile.reason(e)
                    + "; the replay goes on without the file");
            alarms = Writer.nullWriter();
        }
    }

    /**
     * Prints an alarm: the first ten in full, {@code also} after the explanation ("", or what a shield did); the
     * first with the states the model could be in.
     */
    static void print(PrintWriter out, Alarm a, long unit, String also) {
        if (a.number() > PRINTED) {
            return;
        }
        out.println("violation " + a.number() + " at t=" + units(a.micros(), unit) + ": " + a.explanation() + also);
        if (a.number() == 1) {
            for (Alarm.State s : a.states()) {
                out.println("  the model could be in " + String.join(", ", s.locations()) + (s.variables().isEmpty()
                        ? "" : " with " + s.variables()) + (s.clocks().isEmpty() ? "" : ", " + s.clocks()));
            }
            if (a.moreStates() > 0) {
                out.println("  and " + a.moreStates() + " more states");
            }
        }
        if (a.number() == PRINTED) {
            out.println("(further violations are counted, not printed)");
        }
    }

    /**
     * The {@code --junit} case {@code name} of a replay or a run watched on a bus (a violation a failure with the
     * first, missing evidence an error, else a pass): {@code violations} and the {@code first} of them (null if not
     * seen), with times in units of {@code unitMicros}; {@code missing} says what evidence was missing (null: none).
     */
    static JunitXml.Case junitCase(String name, int violations, Alarm first, long unitMicros, String missing) {
        if (violations > 0) {
            String what = first == null ? violations + " violations"
                    : "violation " + first.number() + " at t=" + MonitorCommand.units(first.micros(), unitMicros) + ": "
                            + first.explanation() + (violations > 1 ? " (" + violations + " violations in all)" : "");
            return new JunitXml.Case(name, "failure", "VIOLATION", what);
        }
        if (missing != null) {
            return new JunitXml.Case(name, "error", "INCOMPLETE", missing);
        }
        return new JunitXml.Case(name, null, null, "no violation");
    }

    /** The violations counted, in words: {@code no violation}, {@code 1 violation}, {@code 2 violations}. */
    static String violations(int v) {
        return v == 0 ? "no violation" : v + " violation" + (v == 1 ? "" : "s");
    }

    /** The events checked, in words: {@code 1 event checked}, {@code 2 events checked}. */
    static String events(long e) {
        return e + " event" + (e == 1 ? "" : "s") + " checked";
    }

    /** The lines of a trace rejected, in words: {@code 0 lines rejected}, {@code 1 line rejected}. */
    static String rejected(int lines) {
        return lines + " line" + (lines == 1 ? "" : "s") + " rejected";
    }

    /** A time on the run's clock in time units, with three decimals. */
    static String units(long micros, long unit) {
        long whole = Math.floorDiv(micros, unit);
        long rest = Math.floorMod(micros, unit) * 1000 / unit;
        return whole + "." + String.format(Locale.ROOT, "%03d", rest);
    }

    private ParameterException usage(String message) {
        return new ParameterException(spec.commandLine(), "dtron monitor: " + message);
    }
}
