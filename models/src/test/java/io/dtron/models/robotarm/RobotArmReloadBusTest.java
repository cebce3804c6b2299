package io.dtron.models.robotarm;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannelValued;
import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.ShellWords;
import io.dtron.testsupport.Waits;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Model versions handed to a controller on the bus during its run ({@code dtron control --reload-from-bus}, {@code
 * dtron reload}): the control page's session runs as written, on a JGroups bus of the test's with the arm's Java plant
 * ({@link RobotArmPlant}) in its own JVM, at 250 ms a time unit. The version that passes its queries is accepted and
 * then taken at a reset point, and the sender hears both; the version whose query fails is refused with that query,
 * and the sender hears it; a malformed message is refused, the sender told why, and counted. The run goes on
 * throughout: it lasts its duration without alarm. The printed lines are the page's but for the times, the versions'
 * numbers and the member ids, which differ from run to run.
 */
@Timeout(value = 4, unit = TimeUnit.MINUTES)
class RobotArmReloadBusTest {
    private static final String PROMPT = "$ java -jar dtron.jar ";
    private static final Pattern TAKEN = Pattern.compile("taken at t=([0-9.]+) \\(a reset point\\)");

    @TempDir
    Path dir;

    @Test
    void thePagesVersionsAreTakenAndRefusedMidRunAndTheSenderHearsIt() throws Exception {
        List<String> page = DocPage.read("control.md").blockAfter("### From the bus").code().lines().toList();
        String plantPrefix = ArmProcess.PAGE_PREFIX;
        assertTrue(page.get(0).startsWith(plantPrefix) && page.get(0).endsWith(" > /tmp/arm.log &"), page.get(0));
        assertTrue(page.get(1).startsWith(PROMPT + "control ") && page.get(1).endsWith(" > /tmp/control.log &"),
                page.get(1));
        String cluster = "reload-" + UUID.randomUUID().toString().substring(0, 8);
        Path log = dir.resolve("arm.log");
        Process plant = ArmProcess.start(ArmProcess.args(page.get(0).substring(plantPrefix.length(),
                page.get(0).indexOf(" >")), cluster), log);
        try {
            StringWriter controlOut = new StringWriter();
            StringWriter controlErr = new StringWriter();
            List<String> control = ArmProcess.args(page.get(1).substring(PROMPT.length(), page.get(1).indexOf(" >")),
                    cluster);
            CompletableFuture<Integer> controller = CompletableFuture.supplyAsync(() -> DtronCommand.run(
                    control.toArray(String[]::new), new PrintWriter(controlOut, true), new PrintWriter(controlErr,
                            true)));
            Waits.await("the controller runs and takes versions from the bus").until(() -> controller.isDone()
                    || controlOut.toString().contains("; model versions are taken from the bus\n"));
            assertFalse(controller.isDone(), controlOut + "" + controlErr);

            // the page's reloads, one after the other, each with what the page says it prints
            List<Integer> exits = new ArrayList<>();
            List<String> taken = new ArrayList<>();
            int at = 2;
            while (at < page.size()) {
                String line = page.get(at);
                assertTrue(line.startsWith(PROMPT + "reload "), line);
                int end = at + 1;
                while (end < page.size() && !page.get(end).startsWith("$ ")) {
                    end++;
                }
                StringWriter out = new StringWriter();
                StringWriter err = new StringWriter();
                int exit = DtronCommand.run(ArmProcess.args(line.substring(PROMPT.length()), cluster)
                        .toArray(String[]::new), new PrintWriter(out, true), new PrintWriter(err, true));
                String shown = "exit " + exit + "\n" + out + err + "\ncontroller:\n" + controlOut + controlErr;
                assertEquals(masked(page.subList(at + 1, end), "'arm'"), masked(ShellWords.lines(out.toString(),
                        ArmProcess.ROOT), "'" + cluster + "'"), shown);
                assertEquals("", err.toString(), shown);
                Matcher t = TAKEN.matcher(out.toString());
                if (t.find()) {
                    taken.add(t.group(1));
                }
                exits.add(exit);
                at = end;
            }
            assertEquals(List.of(0, 2), exits, "taken, refused: " + controlOut);

            // a malformed version: refused with the reason, told to its sender, counted
            String refusal = malformed(cluster);
            assertTrue(refusal.matches("model version bus version 7 from \\S+ refused: malformed: .+"), refusal);

            int exit = controller.get(3, TimeUnit.MINUTES);
            String shown = "exit " + exit + "\n" + controlOut + controlErr + "\nplant:\n" + Files.readString(log);
            assertEquals(0, exit, shown);
            assertTrue(plant.waitFor(30, TimeUnit.SECONDS), "the plant leaves after its run: " + shown);
            // the controller took the version where its sender heard it was taken, at a reset point of the run
            assertEquals(1, taken.size(), shown);
            assertTrue(controlOut.toString().contains("\nmodel version robot-arm-v2.xta (bus version ")
                    && controlOut.toString().contains(" taken at t=" + taken.get(0) + " (a reset point)\n"), shown);
            assertTrue(controlOut.toString().contains(" refused: query [2] A[] (Arm.Moving imply Arm.y <= 5) is NOT"
                    + " satisfied; the run goes on with the one it has\n"), shown);
            assertTrue(controlOut.toString().lines().anyMatch(l -> l.startsWith("control COMPLETED at t=120.000: ")
                    && l.endsWith(", 0 alarms, 1 model version taken, 2 refused (seed 1)")), shown);
            assertFalse(Files.readString(log).contains("ignored: "), "every command came in a state that takes it: "
                    + shown);
        } finally {
            plant.destroyForcibly();
        }
    }

    /** Sends a version that is no JSON object, as version 7, and returns the controller's answer. */
    private static String malformed(String cluster) throws Exception {
        BlockingQueue<String> answers = new LinkedBlockingQueue<>();
        try (Dtron member = Dtron.connect(DtronOptions.builder().clusterName(cluster)
                .bindAddress(InetAddress.getLoopbackAddress()).build())) {
            member.addDtronListener(new DtronListener(Dtron.MODEL_OUTCOME) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    if (message.getVariables().get("version") == 7) {
                        answers.add(message.getVariables().get("outcome") + " " + message.getText());
                    }
                }
            });
            member.send(Dtron.MODEL_VERSION.constructValued(Map.of("version", 7)), "chan i_move; // not JSON");
            String answer = answers.poll(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS);
            assertTrue(answer != null && answer.startsWith("2 "), "the controller refused it: " + answer);
            return answer.substring(2);
        }
    }

    /** The lines with the times, the versions' numbers and the member ids masked, and the bus named alike. */
    private static List<String> masked(List<String> lines, String bus) {
        return lines.stream().map(l -> l.replace(bus, "BUS").replaceAll("t=[0-9]+\\.[0-9]{3}", "t=T")
                .replaceAll("version [0-9]+", "version N").replaceAll("dtron-[0-9]+-[0-9a-f]{8}", "MEMBER")).toList();
    }
}
