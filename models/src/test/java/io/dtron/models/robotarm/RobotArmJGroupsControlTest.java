package io.dtron.models.robotarm;

import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.HexFormat;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.ThreadLocalRandom;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron control --cluster NAME --key-file FILE} against the robot arm's Java plant ({@link RobotArmPlant}) in
 * its own JVM on the embedded JGroups bus on loopback, both holding the test's key file, in real time at 250 ms a time
 * unit (as {@link RobotArmBusControlTest} on NATS, for the same reason: the arm's narrowest windows are 1 unit wide).
 * What the model guarantees: the correct arm is controlled for the run's whole duration with no alarm and never gets
 * the safe action; the stalling arm raises the alarm once the model's deadline, 5 units after the move, has passed,
 * naming the missing reading, and the plant receives the safe action, stop; that run is the control page's two
 * command lines as written (on a bus name of the test's, the plant's JVM on the test's class path, the default key
 * file). The controller prints the bus's summary at the end, as {@code dtron run} does.
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class RobotArmJGroupsControlTest {
    private static final String ARM = "src/main/resources/io/dtron/models/robotarm/robot-arm.xta";

    @TempDir
    Path dir;

    /** The bus's secret, in a key file of the test's that only its owner reads. */
    private Path keyFile() throws Exception {
        byte[] secret = new byte[32];
        ThreadLocalRandom.current().nextBytes(secret);
        Path key = dir.resolve("bus.key");
        Files.writeString(key, HexFormat.of().formatHex(secret) + "\n");
        Files.setPosixFilePermissions(key, PosixFilePermissions.fromString("rw-------"));
        return key;
    }

    /**
     * Starts the plant's JVM with {@code plantArgs} (after its class name) and runs {@code dtron control} with {@code
     * controlArgs}, both on the bus {@code cluster} of the test's.
     */
    private ArmControl.Run control(List<String> plantArgs, List<String> controlArgs) throws Exception {
        Path log = dir.resolve("plant.log");
        return ArmControl.control(ArmProcess.start(plantArgs, log), log, controlArgs);
    }

    /** The summary of the bus that ends a run on it: who served what, the latencies and the counters. */
    private static void assertBusSummary(ArmControl.Run run) {
        assertTrue(run.out().lines().anyMatch(l -> l.startsWith("dtron control: every command and reading is served; ")
                && l.endsWith(" receives [grip, move, release, stop] and sends [arrived, gripped]")), run.shown());
        assertTrue(run.out().contains("\nlatency t2 - t1 of outputs: "), run.shown());
        assertTrue(run.out().contains("\nbus: "), run.shown());
    }

    @Test
    void theCorrectArmIsControlledForTheWholeRunWithoutAlarm() throws Exception {
        String cluster = "arm-" + UUID.randomUUID().toString().substring(0, 8);
        String key = keyFile().toString();
        ArmControl.Run run = control(List.of("--cluster", cluster, "--key-file", key, "--runs", "1"), List.of("control",
                ARM, "--cluster", cluster, "--key-file", key, "--duration", "40", "--timeunit", "250000", "--seed", "1",
                "--safe-action", "i_stop", "--wait-timeout", "60"));
        ArmControl.assertControlledWithoutAlarm(run);
        assertTrue(run.out().contains("against the plant on bus '" + cluster + "' at 127.0.0.1"), run.shown());
        assertBusSummary(run);
        // 40 units of 250 ms: a progress line every five seconds of the run's ten
        String out = run.out().replace(System.lineSeparator(), "\n");
        Matcher progress = Pattern.compile("\nprogress: \\d+ s elapsed, \\d+ commands? sent, \\d+ readings?(, the last"
                + " at t=\\d+\\.\\d{3})?\n").matcher(out);
        assertTrue(progress.find(), run.shown());
        assertTrue(progress.start() < out.indexOf("control COMPLETED"), run.shown());
    }

    @Test
    void thePagesStallingArmRaisesTheAlarmAtTheModelsDeadlineAndIsStopped() throws Exception {
        List<String> page = DocPage.read("control.md").blockAfter("## A plant in Java").code().lines().toList();
        String prefix = ArmProcess.PAGE_PREFIX;
        assertTrue(page.get(0).startsWith(prefix), page.get(0));
        assertTrue(page.get(1).startsWith("$ java -jar dtron.jar control "), page.get(1));
        String cluster = "page-" + UUID.randomUUID().toString().substring(0, 8);
        // the page's lines as written, on the test's bus and with the test's class path for the plant's JVM
        ArmControl.Run run = control(ArmProcess.args(page.get(0).substring(prefix.length()), cluster),
                ArmProcess.args(page.get(1).substring("$ java -jar dtron.jar ".length()), cluster));
        ArmControl.assertStoppedAfterTheDeadline(run);
        assertBusSummary(run);
    }
}
