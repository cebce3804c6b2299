package io.dtron.models.robotarm;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageSessions;
import io.dtron.testsupport.ShellWords;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The control page ({@code control.md}): its model and queries are the sample's files, and its {@code $ java -jar
 * dtron.jar control ...} sessions, run as written from the checkout's folder, in virtual time, print exactly what the
 * page shows, with the exit codes it says.
 */
class ControlPageTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    private static final Path SAMPLE = ROOT.resolve("models/src/main/resources/io/dtron/models/robotarm");

    @Test
    void theModelAndQueriesAreTheSamples() throws Exception {
        DocPage page = DocPage.read("control.md");
        assertEquals(Files.readString(SAMPLE.resolve("robot-arm.xta"), StandardCharsets.UTF_8),
                page.blocks("xta").get(0));
        assertEquals(Files.readString(SAMPLE.resolve("robot-arm.q"), StandardCharsets.UTF_8),
                page.blockAfter("The arm's queries, `robot-arm.q`").code());
    }

    @Test
    void everySessionPrintsWhatThePageShows() throws Exception {
        DocPage page = DocPage.read("control.md");
        List<String> exits = new ArrayList<>();
        for (PageSessions.Session s : PageSessions.of(page, word -> word.startsWith("models/")
                ? ROOT.resolve(word).toString() : word)) {
            PageSessions.Printed run = PageSessions.run(DtronCommand::run, s);
            // progress lines come every five seconds of a run: on a busy machine, a session may last that long
            List<String> printed = new ArrayList<>(ShellWords.lines(run.out(), ROOT).stream()
                    .filter(l -> !l.startsWith("progress: ")).toList());
            printed.addAll(ShellWords.lines(run.err(), ROOT));
            assertEquals(s.expected(), printed, "control.md, the session on line " + s.line());
            exits.add(s.args().get(0) + ": " + run.exit());
        }
        assertEquals(List.of("control: 0", "control: 2", "control: 2", "control: 0", "control: 0"), exits);
        String text = page.text();
        assertTrue(text.contains("The exit code is 0. Mutant 7") && text.contains("The exit code is 2.\n"),
                "the page says the exit codes the runs give");
    }
}
