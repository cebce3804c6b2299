package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannelValued;
import io.dtron.cli.DtronCommand;
import io.dtron.models.lamp.LampBusAdapter;
import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.Waits;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor MODEL --cluster NAME} (and {@code --bus nats://...}) beside a live {@code dtron run} of the
 * ticker on the same bus, real JGroups members on loopback (a real nats-server): the monitor agrees with the tester
 * (no alarm where the run PASSED: it judges up to the tester's end of observation, which the run's stop carries), finds the slow ticker's late tick at the deadline it missed, publishes the alarm
 * and its verdict on {@code dtron_alarm} where another member receives them, and raises no false alarm when it joins
 * a run already going.
 */
@Timeout(value = 5, unit = TimeUnit.MINUTES)
public class LiveMonitorTest {
    private static final String MODEL = "src/main/resources/io/dtron/models/ticker.xml";
    private static final Pattern VIOLATION = Pattern.compile("(?m)^violation 1 at t=(\\d+)\\.(\\d{3}): (.*)$");

    @TempDir
    Path dir;

    /** How a command ended. */
    public record Result(int exit, String out, String err) {
        /** The exit code and the output, for a failed assertion. */
        public String shown() {
            return "exit " + exit + "\n" + out + err;
        }
    }

    /** A command of dtron's in this JVM, on a thread of its own; its output as it comes. */
    public static final class Command {
        final StringWriter out = new StringWriter();
        final StringWriter err = new StringWriter();
        final CompletableFuture<Result> result;

        /** Starts {@code dtron ARGS}. */
        public Command(List<String> args) {
            result = CompletableFuture.supplyAsync(() -> {
                int exit = DtronCommand.run(args.toArray(String[]::new), new PrintWriter(out, true),
                        new PrintWriter(err, true));
                return new Result(exit, out.toString(), err.toString());
            });
        }

        /** Waits for the end. */
        public Result get() throws Exception {
            return result.get(4, TimeUnit.MINUTES);
        }
    }

    static String cluster(String what) {
        return what + "-" + UUID.randomUUID().toString().substring(0, 8);
    }

    /** The tester's run of the ticker: 10 ms time units, as the README's. */
    static List<String> run(String variant, List<String> bus, int timeoutUnits, Path trace) {
        return run(variant, bus, 10_000, timeoutUnits, trace);
    }

    static List<String> run(String variant, List<String> bus, long unit, int timeoutUnits, Path trace) {
        List<String> args = new ArrayList<>(List.of(MODEL, "--adapter", TickerBusAdapter.class.getName() + ":"
                + variant, "--timeunit", String.valueOf(unit), "--timeout", String.valueOf(timeoutUnits),
                "--delay-policy", "eager", "--trace", trace.toString()));
        args.addAll(bus);
        return args;
    }

    /** Starts the monitor of the ticker on the bus and waits until it is a member. */
    static Command monitor(List<String> bus, String... more) {
        return monitor(MODEL, bus, more);
    }

    /** Starts the monitor of {@code model} on the bus and waits until it is a member. */
    public static Command monitor(String model, List<String> bus, String... more) {
        List<String> args = new ArrayList<>(List.of("monitor", model));
        args.addAll(bus);
        args.addAll(List.of(more));
        Command monitor = new Command(args);
        Waits.await("the monitor on the bus").until(() -> monitor.out.toString().contains(" as ")
                || monitor.result.isDone());
        return monitor;
    }

    /** A member that only listens to the alarms (and the runs' starts), as a safety controller would. */
    static final class AlarmListener implements AutoCloseable {
        final List<IDtronChannelValued> received = new CopyOnWriteArrayList<>();
        final List<IDtronChannelValued> starts = new CopyOnWriteArrayList<>();
        final Dtron dtron;

        AlarmListener(DtronOptions.Builder options) {
            dtron = Dtron.connect(options.build());
            dtron.addDtronListener(new DtronListener(Dtron.ALARM) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    received.add(message);
                }
            });
            dtron.addDtronListener(new DtronListener(Dtron.RUN_START) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    starts.add(message);
                }
            });
        }

        @Override
        public void close() {
            dtron.close();
        }
    }

    @Test
    void aCorrectRunGivesNoAlarmAndTheSlowTickersLateTickIsFoundWhereItWasDue() throws Exception {
        String name = cluster("live");
        List<String> bus = List.of("--cluster", name);
        try (AlarmListener safety = new AlarmListener(DtronOptions.builder().clusterName(name)
                .bindAddress(InetAddress.getLoopbackAddress()))) {
            Command correctMonitor = monitor(bus);
            Result tester = new Command(run("correct", bus, 100, dir.resolve("correct.jsonl"))).get();
            Result watched = correctMonitor.get();
            if (tester.exit() == 0) {
                agreesWithAPassedRun(watched.out(), watched.shown() + tester.shown());
            } else if (tester.exit() == 2) {
                assertEquals(2, watched.exit(), "the run FAILED, yet:\n" + watched.shown() + tester.shown());
            }
            assertTrue(watched.out().contains(" started (time units of 10000 us)"), watched.shown());
            // the verdict: no violation (reason 0) or the violations the monitor printed
            Waits.await("the first verdict on dtron_alarm").until(() -> safety.received.stream()
                    .anyMatch(m -> m.getVariables().get("verdict") == 1));

            safety.received.clear();
            Command slowMonitor = monitor(bus);
            Path trace = dir.resolve("slow.jsonl");
            Result slow = new Command(run("slow", bus, 300, trace)).get();
            assertEquals(2, slow.exit(), slow.shown());
            Result found = slowMonitor.get();
            assertEquals(2, found.exit(), found.shown());
            Matcher m = VIOLATION.matcher(found.out());
            assertTrue(m.find(), found.shown());
            long alarm = Long.parseLong(m.group(1)) * 10_000 + Long.parseLong(m.group(2)) * 10;
            // the tick the tester failed (later ticks may follow it in the trace, within the tester's window)
            Matcher failed = Pattern.compile("(?m)^FAILED: output tick\\(seq=\\d+\\) observed at t=(\\d+)\\.(\\d{3})")
                    .matcher(slow.out());
            assertTrue(failed.find(), slow.shown());
            long late = Long.parseLong(failed.group(1)) * 10_000 + Long.parseLong(failed.group(2)) * 10;
            // the deadline the late tick missed: before it, at most the model's 2 units of tolerance earlier
            assertTrue(alarm <= late && alarm > late - 30_000, "alarm at " + alarm + " us, the late tick at " + late
                    + " us:\n" + found.shown() + slow.shown());
            assertTrue(m.group(3).startsWith("no event by"), found.shown());
            // the alarm, then the verdict, reached the other member: a missed deadline (3), then 1 violation
            Waits.await("the alarm and the verdict on dtron_alarm").until(() -> safety.received.size() >= 2);
            IDtronChannelValued first = safety.received.get(0);
            assertEquals(3, first.getVariables().get("reason"), first.toString());
            assertEquals(0, first.getVariables().get("verdict"), first.toString());
            IDtronChannelValued verdict = safety.received.get(1);
            assertEquals(1, verdict.getVariables().get("verdict"), verdict.toString());
            assertEquals(1, verdict.getVariables().get("number"), verdict.toString());
        }
    }

    @Test
    void oneMonitorFollowsThreeRunsAndAttributesEachAlarmAndVerdictToItsRun() throws Exception {
        String name = cluster("runs");
        List<String> bus = List.of("--cluster", name);
        try (AlarmListener safety = new AlarmListener(DtronOptions.builder().clusterName(name)
                .bindAddress(InetAddress.getLoopbackAddress()))) {
            Command monitor = monitor(bus, "--runs", "3");
            Result first = new Command(run("correct", bus, 100, dir.resolve("first.jsonl"))).get();
            Result slow = new Command(run("slow", bus, 300, dir.resolve("slow.jsonl"))).get();
            Result last = new Command(run("correct", bus, 100, dir.resolve("last.jsonl"))).get();
            Result watched = monitor.get();
            String all = watched.shown() + first.shown() + slow.shown() + last.shown();
            assertEquals(2, slow.exit(), all);
            // the slow run's violation makes the watch's exit code 2, whatever the others'
            assertEquals(2, watched.exit(), all);
            Waits.await("the three runs' starts").until(() -> safety.starts.size() >= 3);
            List<String> ids = safety.starts.stream().map(IDtronChannelValued::getRunId).toList();
            assertEquals(3, ids.stream().distinct().count(), ids.toString());
            String out = watched.out();
            for (String id : ids) {
                assertTrue(out.contains("run " + id + " started (time units of 10000 us)"), all);
            }
            // a run ends at its stop, or at its first violation; the slow one at the deadline its late tick missed
            List<Result> testers = List.of(first, slow, last);
            List<String> perRun = new ArrayList<>();
            List<Integer> counts = new ArrayList<>();
            for (int i = 0; i < 3; i++) {
                int from = out.indexOf("run " + ids.get(i) + " started");
                Matcher ended = Pattern.compile("(?m)^run " + ids.get(i) + " ended: (no violation|(\\d+) violations?),"
                        + " \\d+ events? checked \\((the run ended|stopped at the first violation)\\)").matcher(out);
                assertTrue(ended.find(from), "run " + (i + 1) + ":\n" + all);
                int violations = ended.group(2) == null ? 0 : Integer.parseInt(ended.group(2));
                counts.add(violations);
                perRun.add("run " + ids.get(i) + ": " + violations);
                if (testers.get(i).exit() == 0) {
                    agreesWithAPassedRun(out.substring(from, ended.end()), "run " + (i + 1) + ":\n" + all);
                } else if (testers.get(i).exit() == 2) {
                    assertEquals(1, violations, "run " + (i + 1) + " FAILED, yet:\n" + all);
                    assertEquals("stopped at the first violation", ended.group(3), all);
                }
            }
            assertTrue(out.contains("dtron monitor: 3 runs, ") && out.contains("(" + String.join(", ", perRun)
                    + ")"), all);
            // on dtron_alarm: the verdict of each run, in order, each with its run's id; the slow run's missed
            // deadline (3) with the slow run's id, before its verdict
            Waits.await("three verdicts on dtron_alarm").until(() -> safety.received.stream()
                    .filter(m -> m.getVariables().get("verdict") == 1).count() >= 3);
            List<IDtronChannelValued> verdicts = safety.received.stream()
                    .filter(m -> m.getVariables().get("verdict") == 1).toList();
            for (int i = 0; i < 3; i++) {
                assertEquals(ids.get(i), verdicts.get(i).getRunId(), verdicts.toString());
            }
            for (int i = 0; i < 3; i++) {
                // each run's verdict counts that run's violations, and each alarm carries its run's id
                String id = ids.get(i);
                assertEquals(counts.get(i), verdicts.get(i).getVariables().get("number"), verdicts.toString());
                assertEquals(counts.get(i).longValue(), safety.received.stream().filter(m -> m.getVariables().get("verdict") == 0
                        && m.getRunId().equals(id)).count(), safety.received.toString());
            }
            assertEquals(3 + counts.stream().mapToInt(Integer::intValue).sum(), safety.received.size(),
                    safety.received.toString());
            List<IDtronChannelValued> slowAlarms = safety.received.stream()
                    .filter(m -> m.getRunId().equals(ids.get(1))).toList();
            assertEquals(2, slowAlarms.size(), slowAlarms.toString());
            assertEquals(3, slowAlarms.get(0).getVariables().get("reason"), slowAlarms.toString());
            assertEquals(0, slowAlarms.get(0).getVariables().get("verdict"), slowAlarms.toString());
        }
    }

    /**
     * Asserts that the monitor's lines of a run its tester PASSED agree with it: no violation. Before the monitor lets
     * a deadline pass, it asks the adapters as the tester does, and their answers bring what they sent before, however
     * long their messages took; a member that does not answer is given as long as the tester gives it.
     */
    static void agreesWithAPassedRun(String runLines, String shown) {
        assertFalse(Pattern.compile("(?m)^violation \\d+ at").matcher(runLines).find(), "the run PASSED, yet:\n"
                + shown);
    }

    @Test
    void theMonitorBesideTheSmartLampOnTheBusAgreesWithTheTester() throws Exception {
        Path shared = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        String model = shared.resolve("LightContr.xml").toString();
        List<String> lamp = List.of("--interface", shared.resolve("LightContr.trn").toString());
        String name = cluster("lamp");
        List<String> bus = List.of("--cluster", name);
        for (String variant : List.of("correct", "late")) {
            List<String> monitorArgs = new ArrayList<>(List.of("monitor", model));
            monitorArgs.addAll(lamp);
            monitorArgs.addAll(bus);
            Command monitor = new Command(monitorArgs);
            Waits.await("the monitor on the bus").until(() -> monitor.out.toString().contains(" as ")
                    || monitor.result.isDone());
            List<String> runArgs = new ArrayList<>(List.of(model, "--adapter", LampBusAdapter.class.getName() + ":"
                    + variant, "--timeunit", "10000", "--timeout", "300", "--delay-policy", "eager"));
            runArgs.addAll(lamp);
            runArgs.addAll(bus);
            Result tester = new Command(runArgs).get();
            Result watched = monitor.get();
            String both = watched.shown() + tester.shown();
            if (tester.exit() == 0) {
                agreesWithAPassedRun(watched.out(), both);
            } else if (tester.exit() == 2) {
                assertEquals(2, watched.exit(), "the run FAILED, yet:\n" + both);
                Matcher m = VIOLATION.matcher(watched.out());
                assertTrue(m.find(), both);
                // the tester found the late level when the deadline had passed, as the monitor did
                Matcher failed = Pattern.compile("(?m)^FAILED: .* at t=(\\d+)\\.(\\d{3})").matcher(tester.out());
                if (failed.find()) {
                    assertTrue(Long.parseLong(m.group(1)) * 1000 + Long.parseLong(m.group(2))
                            <= Long.parseLong(failed.group(1)) * 1000 + Long.parseLong(failed.group(2)), both);
                }
            }
            if (variant.equals("late")) {
                assertEquals(2, tester.exit(), both);
            }
        }
    }

    @Test
    void aMonitorThatJoinsARunningSystemRaisesNoFalseAlarm() throws Exception {
        String name = cluster("midway");
        List<String> bus = List.of("--cluster", name);
        Path trace = dir.resolve("midway.jsonl");
        // 20 ticks of half a second: the monitor joins after the first, between a reset and a tick or a tick and
        // the next, knowing neither the tick's number nor the clocks' values
        Command tester = new Command(run("correct", bus, 50_000, 200, trace));
        Waits.await("the run's first tick").until(() -> Files.exists(trace) && Files.readString(trace)
                .contains("{\"kind\":\"output\"") || tester.result.isDone());
        // a monitor that joins knows no run start: it is told the run's time unit
        Command monitor = monitor(bus, "--timeunit", "50000", "--duration", "30");
        Result run = tester.get();
        Result watched = monitor.get();
        assertTrue(watched.out().contains("from every reachable state (it joins a running system)"), watched.shown());
        if (run.exit() == 0) {
            assertEquals(0, watched.exit(), "the run PASSED, yet:\n" + watched.shown() + run.shown());
            assertTrue(watched.out().contains("no violation"), watched.shown());
        }
    }

    @Test
    void onNatsTheMonitorAgreesAndItsAlarmReachesAnotherMember() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            String name = cluster("nats-live");
            List<String> bus = List.of("--bus", server.url(), "--cluster", name);
            try (AlarmListener safety = new AlarmListener(DtronOptions.builder().clusterName(name)
                    .natsServers(List.of(server.url())))) {
                Command correct = monitor(bus);
                Result tester = new Command(run("correct", bus, 100, dir.resolve("correct.jsonl"))).get();
                Result watched = correct.get();
                if (tester.exit() == 0) {
                    agreesWithAPassedRun(watched.out(), watched.shown() + tester.shown());
                }
                Command slowMonitor = monitor(bus);
                Result slow = new Command(run("slow", bus, 300, dir.resolve("slow.jsonl"))).get();
                assertEquals(2, slow.exit(), slow.shown());
                Result found = slowMonitor.get();
                assertEquals(2, found.exit(), found.shown());
                Waits.await("the alarm on dtron_alarm").until(() -> safety.received.stream()
                        .anyMatch(m -> m.getVariables().get("verdict") == 0 && m.getVariables().get("reason") == 3));
            }
        }
    }
}
