package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageSessions;
import io.dtron.testsupport.ShellWords;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The {@code $ java -jar dtron.jar ...} sessions of the goals page ({@code goals.md}) run as written, in order, in
 * this JVM, in one folder holding the shared {@code LightContr.xml} and {@code .trn} and the page's own trap models:
 * the runs are in virtual time, so each prints exactly what the page shows; of {@code dtron verify}'s lines, only
 * the time and memory of each query are left out of the comparison.
 */
class GoalsPageTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");

    @Test
    void everySessionPrintsWhatThePageShows(@TempDir Path dir) throws Exception {
        Files.copy(SHARED.resolve("tron/LightContr.xml"), dir.resolve("LightContr.xml"));
        Files.copy(SHARED.resolve("tron/LightContr.trn"), dir.resolve("LightContr.trn"));
        DocPage page = DocPage.read("goals.md");
        Files.writeString(dir.resolve("lamp-traps.xta"), page.blocks("xta").get(0));
        Files.writeString(dir.resolve("lamp-traps-2.xta"), page.blocks("xta").get(1));
        List<String> exits = new ArrayList<>();
        for (PageSessions.Session s : PageSessions.of(page, PageSessions.inFolder(dir, "xml|trn|xta", ROOT))) {
            PageSessions.Printed run = PageSessions.run(DtronCommand::run, s);
            List<String> printed = new ArrayList<>(ShellWords.lines(run.out(), dir));
            printed.addAll(ShellWords.lines(run.err(), dir));
            assertEquals(s.expected().stream().map(GoalsPageTest::untimed).toList(),
                    printed.stream().map(GoalsPageTest::untimed).toList(), "goals.md, the session on line " + s.line());
            exits.add(s.args().get(0) + ": " + run.exit());
        }
        assertEquals(List.of("run: 0", "run: 0", "run: 0", "run: 3", "verify: 2", "verify: 0"), exits);
        String text = page.text();
        assertEquals(true, text.contains("The exit code is 2") && text.contains("INCONCLUSIVE (exit code 3)"),
                "the page says the exit codes the runs give");
    }

    /** A line of dtron verify without the time and memory a query took, which change from run to run. */
    private static String untimed(String line) {
        return line.replaceAll(", [0-9.]+ s, [0-9]+ MB\\)", ", T s, M MB)");
    }
}
