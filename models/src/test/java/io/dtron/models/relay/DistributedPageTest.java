package io.dtron.models.relay;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.ShellSession;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
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
 * The sessions of {@code distributed.md} run as they are, by {@code bash} in the project's folder (where their paths
 * point), after the build made {@code dtron.jar} and the models' classes: the relay's two testers with its adapters,
 * then the conversation of two models. Only the bus names change ({@code lab} and {@code talk}, to the test's own),
 * the build command is left out (the build ran it), and a final {@code wait} collects what the session left in the
 * background. Every tester must pass, and none may warn that the bus's delays take a large share of its model's
 * narrowest window, nor reject a message (the other tester's channels are not rejected).
 */
@Timeout(value = 300, unit = TimeUnit.SECONDS)
class DistributedPageTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    private static final String BUILD = "mvn -B -q -DskipTests package";
    private static final Pattern BUS_NAME = Pattern.compile("--cluster (\\w+)");

    @TempDir
    Path dir;

    @Test
    void theRelayAndTheConversationOfThePagePassWithoutWarnings() throws Exception {
        assertTrue(Files.isRegularFile(ROOT.resolve("dtron-cli/target/dtron.jar")),
                "the page runs dtron-cli/target/dtron.jar: build it first (mvn install)");
        DocPage page = DocPage.read("distributed.md");
        List<String> relay = commands(page.blockAfter("## The relay sample").code());
        assertEquals(BUILD, relay.get(0), "the relay's session builds DTRON first");
        List<String> variables = relay.subList(1, 2);
        assertTrue(variables.get(0).startsWith("M="), "then names the models' folder: " + variables);

        String relayOutput = run("relay", relay.subList(1, relay.size()));
        assertAllPassed(relayOutput, 2);
        // the conversation's session uses the variables the relay's set
        List<String> conversation = new ArrayList<>(variables);
        conversation.addAll(commands(page.blockAfter("## A conversation of two models").code()));
        assertAllPassed(run("conversation", conversation), 2);
    }

    /** The commands of a session: its lines after {@code $ }. */
    private static List<String> commands(String session) {
        List<String> commands = new ArrayList<>();
        for (String line : session.split("\n")) {
            if (!line.startsWith("$ ")) {
                fail("a session of the page shows only commands: " + line);
            }
            commands.add(line.substring(2));
        }
        return commands;
    }

    /** Runs the commands with bash in the project's folder, on a bus of the test's own; returns what they printed. */
    private String run(String name, List<String> commands) throws Exception {
        List<String> script = new ArrayList<>();
        String bus = name + "-" + UUID.randomUUID().toString().substring(0, 8);
        String pageBus = null;
        for (String command : commands) {
            Matcher m = BUS_NAME.matcher(command);
            if (m.find()) {
                pageBus = m.group(1);
            }
        }
        assertTrue(pageBus != null, "the " + name + " session names its bus with --cluster: " + commands);
        for (String command : commands) {
            script.add(command.replaceAll("\\b" + pageBus + "\\b", bus));
        }
        script.add("wait");
        String output = ShellSession.run(ROOT, script, dir.resolve(name + ".log"), Duration.ofSeconds(240));
        return "the " + name + " session " + script + " printed:\n" + output;
    }

    /** Every tester passed, and none warned about the time unit or rejected a message. */
    private static void assertAllPassed(String output, int testers) {
        output.lines().filter(l -> l.startsWith("dtron run: delays on the bus before the run"))
                .forEach(l -> System.out.println("DistributedPageTest: " + l));
        long passed = output.lines().filter(l -> l.startsWith("PASSED: ")).count();
        assertEquals(testers, passed, output);
        // the starting tester waits for the others' verdicts and prints them (the others may end before its own)
        assertTrue(output.lines().filter(l -> l.matches("tester \\S+ of this run: PASSED")).count() >= testers - 1,
                "the starting tester prints the others' verdicts: " + output);
        assertFalse(output.contains("dtron run: warning"), "no warning about the bus's delays: " + output);
        assertFalse(output.contains("Rejected a message"), output);
    }
}
