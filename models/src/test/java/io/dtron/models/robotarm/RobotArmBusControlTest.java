package io.dtron.models.robotarm;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.models.ticker.NatsClients;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.ShellWords;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
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

    @TempDir
    Path dir;

    /** Runs the controller against the arm, started with {@code flags}, for {@code duration} time units. */
    private ArmControl.Run control(NatsServer server, long duration, String... flags) throws Exception {
        String cluster = "arm-" + UUID.randomUUID().toString().substring(0, 8);
        Path log = dir.resolve(cluster + ".log");
        List<String> command = new ArrayList<>(List.of(NatsClients.python(), PLANT.toString(), "--bus", server.url(),
                "--cluster", cluster, "--runs", "1"));
        command.addAll(List.of(flags));
        Process plant = new ProcessBuilder(command).redirectErrorStream(true).redirectOutput(log.toFile()).start();
        return ArmControl.control(plant, log, List.of("control", ARM, "--bus", server.url(), "--cluster", cluster,
                "--duration", Long.toString(duration), "--timeunit", "250000", "--seed", "1", "--safe-action",
                "i_stop", "--wait-timeout", "60"));
    }

    @Test
    void theCorrectArmIsControlledForTheWholeRunWithoutAlarm() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            ArmControl.Run run = control(server, 40);
            ArmControl.assertControlledWithoutAlarm(run);
            assertTrue(run.out().contains("against the plant on bus 'arm-") && run.out().contains(server.url()),
                    run.shown());
        }
    }

    @Test
    void theStallingArmRaisesTheAlarmAtTheModelsDeadlineAndIsStopped() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            ArmControl.assertStoppedAfterTheDeadline(control(server, 100, "--stall"));
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
            ArmControl.Run run = ArmControl.control(arm, log, args(controlLine.substring("$ java -jar dtron.jar "
                    .length()), server, cluster));
            assertEquals(2, run.exit(), run.shown());
            // progress lines come every five seconds of the run: the page leaves them out
            List<String> printed = new ArrayList<>(ShellWords.lines(run.out(), ROOT).stream()
                    .filter(l -> !l.startsWith("progress: ")).toList());
            // a warning that the commands' margin measured on this machine is wider than a window: load says it
            printed.addAll(ShellWords.lines(run.err(), ROOT).stream()
                    .filter(l -> !l.startsWith("dtron control: warning: the window of input ")).toList());
            assertEquals(masked(page.subList(3, page.size()), "nats://127.0.0.1:4222", "'arm'"),
                    masked(printed, server.url(), "'" + cluster + "'"), run.shown());
            assertTrue(run.plant().contains("stopped at t="), run.shown());
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
