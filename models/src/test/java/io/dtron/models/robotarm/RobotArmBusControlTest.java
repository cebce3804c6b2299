package io.dtron.models.robotarm;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import io.dtron.models.ticker.NatsClients;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.ShellWords;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.math.BigDecimal;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron control --bus nats://...} against the robot arm's Python plant ({@code
 * clients/python/examples/robot_arm.py}) in its own process on a nats-server of the test's, in real time at 250 ms a
 * time unit: the arm's tightest windows, a grip's reading 1 to 2 units after the grip and the release 3 to 4 units
 * after it, are then 250 ms wide (at 100 ms, with two cores kept busy beside the other builds of this machine, a
 * controller thread held up 145 ms and a Python plant whose grip came 2.5 units late were seen). The correct arm: the
 * run lasts its duration, no alarm, the plant never gets the safe action. The stalling arm: the alarm names the
 * missing reading and the model's deadline, 5 units after the move (the arrival window 2 to 5 units after it), comes
 * no earlier than that deadline, and the plant receives the safe action, stop. The control page's session of the
 * stalling arm runs as written, on a server and a bus name of the test's, and prints what the page shows but for the
 * times, the member ids and the bus's figures (latencies, counters, delays), which differ from run to run. Skipped without nats-server or a Python with the dtron
 * package, as the other NATS tests.
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class RobotArmBusControlTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    private static final String ARM = "src/main/resources/io/dtron/models/robotarm/robot-arm.xta";
    private static final Path PLANT = NatsClients.PYTHON.resolve("examples/robot_arm.py");
    static final Pattern ALARM = Pattern.compile("ALARM at t=([0-9.]+): no reading came by t=([0-9.]+): the"
            + " model required the plant to act by then\\. The model allowed these readings: arrived between"
            + " t=([0-9.]+) and t=([0-9.]+) \\(Arm: Moving -> Arrived\\)\\. At the last observation the plant was in"
            + " Arm\\.Moving\\.");

    @TempDir
    Path dir;

    record Run(int exit, String out, String err, String plant) {
        String shown() {
            return "exit " + exit + "\n" + out + err + "\nplant:\n" + plant;
        }
    }

    /** Runs the controller against the arm, started with {@code flags}, for {@code duration} time units. */
    private Run control(NatsServer server, long duration, String... flags) throws Exception {
        String cluster = "arm-" + UUID.randomUUID().toString().substring(0, 8);
        Path log = dir.resolve(cluster + ".log");
        List<String> command = new ArrayList<>(List.of(NatsClients.python(), PLANT.toString(), "--bus", server.url(),
                "--cluster", cluster, "--runs", "1"));
        command.addAll(List.of(flags));
        Process plant = new ProcessBuilder(command).redirectErrorStream(true).redirectOutput(log.toFile()).start();
        try {
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            int exit = DtronCommand.run(new String[] {"control", ARM, "--bus", server.url(), "--cluster", cluster,
                "--duration", Long.toString(duration), "--timeunit", "250000", "--seed", "1", "--safe-action",
                "i_stop", "--wait-timeout", "60"}, new PrintWriter(out, true), new PrintWriter(err, true));
            boolean exited = plant.waitFor(30, TimeUnit.SECONDS);
            Run run = new Run(exit, out.toString(), err.toString(), Files.readString(log));
            assertTrue(exited, "the plant exits after its run: " + run.shown());
            return run;
        } finally {
            plant.destroyForcibly();
        }
    }

    @Test
    void theCorrectArmIsControlledForTheWholeRunWithoutAlarm() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            Run run = control(server, 40);
            assertEquals(0, run.exit(), run.shown());
            assertTrue(run.out().contains("against the plant on bus 'arm-") && run.out().contains(server.url()),
                    run.shown());
            assertTrue(run.out().contains("in real time"), run.shown());
            assertTrue(run.out().lines().anyMatch(l -> l.startsWith("control COMPLETED at t=40.000: ")
                    && l.contains(" 0 alarms")), run.shown());
            assertFalse(run.out().contains("ALARM"), run.shown());
            assertFalse(run.plant().contains("stopped at"), "no safe action was sent: " + run.shown());
            assertFalse(run.plant().contains("ignored"), "every command came in a state that takes it: "
                    + run.shown());
        }
    }

    @Test
    void theStallingArmRaisesTheAlarmAtTheModelsDeadlineAndIsStopped() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            Run run = control(server, 100, "--stall");
            assertEquals(2, run.exit(), run.shown());
            Matcher alarm = ALARM.matcher(run.out());
            assertTrue(alarm.find(), run.shown());
            BigDecimal at = new BigDecimal(alarm.group(1));
            BigDecimal deadline = new BigDecimal(alarm.group(2));
            BigDecimal earliest = new BigDecimal(alarm.group(3));
            assertEquals(deadline, new BigDecimal(alarm.group(4)), run.shown());
            // the window 2 to 5 units after the move: the deadline is the model's bound, MOVE_MAX after the move
            assertEquals(0, deadline.subtract(earliest).compareTo(new BigDecimal("3.000")), run.shown());
            assertTrue(at.compareTo(deadline) > 0, "no alarm before the deadline has passed: " + run.shown());
            assertTrue(run.out().contains("safe action stop() sent at t=" + alarm.group(1)), run.shown());
            // the run ends once the safe action is published, a moment after the alarm in real time
            assertTrue(run.out().lines().anyMatch(l -> l.startsWith("control ALARM at t=") && l.contains(": 2"
                    + " commands sent, 0 readings, 1 alarm, safe action stop() taken")), run.shown());
            assertTrue(run.plant().contains("stopped at t="), "the plant received stop: " + run.shown());
        }
    }

    @Test
    void thePagesSessionPrintsWhatThePageShows() throws Exception {
        List<String> page = DocPage.read("control.md").blockAfter("the stalling arm on a NATS server of its own:")
                .code().lines().toList();
        assertTrue(page.get(0).startsWith("$ nats-server "), page.get(0));
        String plantLine = page.get(1);
        String controlLine = page.get(2);
        assertTrue(plantLine.startsWith("$ python3 clients/python/examples/robot_arm.py ") && plantLine.endsWith(" &"),
                plantLine);
        assertTrue(controlLine.startsWith("$ java -jar dtron.jar control "), controlLine);
        String cluster = "page-" + UUID.randomUUID().toString().substring(0, 8);
        try (NatsServer server = NatsServer.start(dir)) {
            List<String> plant = args(plantLine.substring(2, plantLine.indexOf(" >")), server, cluster);
            plant.set(0, NatsClients.python());
            Path log = dir.resolve("arm.log");
            Process arm = new ProcessBuilder(plant).redirectErrorStream(true).redirectOutput(log.toFile()).start();
            try {
                List<String> control = args(controlLine.substring("$ java -jar dtron.jar ".length()), server,
                        cluster);
                StringWriter out = new StringWriter();
                StringWriter err = new StringWriter();
                int exit = DtronCommand.run(control.toArray(String[]::new), new PrintWriter(out, true),
                        new PrintWriter(err, true));
                assertTrue(arm.waitFor(30, TimeUnit.SECONDS), "the plant leaves after its run");
                String shown = out + "" + err + "\nplant:\n" + Files.readString(log);
                assertEquals(2, exit, shown);
                List<String> printed = new ArrayList<>(ShellWords.lines(out.toString(), ROOT));
                // a warning that the commands' margin measured on this machine is wider than a window: load says it
                printed.addAll(ShellWords.lines(err.toString(), ROOT).stream()
                        .filter(l -> !l.startsWith("dtron control: warning: the window of input ")).toList());
                assertEquals(masked(page.subList(3, page.size()), "nats://127.0.0.1:4222", "'arm'"),
                        masked(printed, server.url(), "'" + cluster + "'"), shown);
                assertTrue(Files.readString(log).contains("stopped at t="), shown);
            } finally {
                arm.destroyForcibly();
            }
        }
    }

    /** The words of a command line of the page, on the test's server and bus, its paths from the checkout. */
    private static List<String> args(String line, NatsServer server, String cluster) {
        List<String> args = new ArrayList<>(ShellWords.split(line));
        for (int a = 0; a < args.size(); a++) {
            String word = args.get(a);
            if (word.equals("nats://127.0.0.1:4222")) {
                args.set(a, server.url());
            } else if (word.equals("arm") && args.get(a - 1).equals("--cluster")) {
                args.set(a, cluster);
            } else if (word.startsWith("models/") || word.startsWith("clients/")) {
                args.set(a, ROOT.resolve(word).toString());
            }
        }
        return args;
    }

    /** The lines with the times, the member ids and the bus's figures masked, and the bus named alike. */
    private static List<String> masked(List<String> lines, String url, String bus) {
        return lines.stream().map(l -> l.replace(url, "URL").replace(bus, "BUS")
                .replaceAll("t=[0-9]+\\.[0-9]{3}", "t=T").replaceAll("dtron-(py-)?[0-9]+-[0-9a-f]{8}", "MEMBER")
                // the bus's figures, and what of the safe action's way back the run still saw
                .replaceAll("^(latency t2 - t1 of [a-z ]+|clock offset of MEMBER to the controller|bus|delays in the"
                        + " run \\([^)]*\\)): .*", "$1: ...")).toList();
    }
}
