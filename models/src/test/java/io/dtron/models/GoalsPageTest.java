package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;

import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.ShellWords;
import java.io.PrintWriter;
import java.io.StringWriter;
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
    private static final String PROMPT = "$ java -jar dtron.jar ";

    @Test
    void everySessionPrintsWhatThePageShows(@TempDir Path dir) throws Exception {
        Files.copy(SHARED.resolve("tron/LightContr.xml"), dir.resolve("LightContr.xml"));
        Files.copy(SHARED.resolve("tron/LightContr.trn"), dir.resolve("LightContr.trn"));
        DocPage page = DocPage.read("goals.md");
        Files.writeString(dir.resolve("lamp-traps.xta"), page.blocks("xta").get(0));
        Files.writeString(dir.resolve("lamp-traps-2.xta"), page.blocks("xta").get(1));
        List<String> exits = new ArrayList<>();
        for (DocPage.Block b : page.blocksStartingWith(PROMPT)) {
            List<String> lines = b.code().lines().toList();
            String command = lines.get(0).substring(PROMPT.length());
            List<String> expected = lines.subList(1, lines.size()).stream().map(GoalsPageTest::untimed).toList();
            List<String> args = ShellWords.split(command);
            for (int a = 0; a < args.size(); a++) {
                if (args.get(a).matches("[\\w-]+\\.(xml|trn|xta)")) {
                    args.set(a, dir.resolve(args.get(a)).toString());
                } else if (args.get(a).equals("models/target/classes")) {
                    args.set(a, ROOT.resolve(args.get(a)).toString());
                }
            }
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            int exit = DtronCommand.run(args.toArray(String[]::new), new PrintWriter(out, true),
                    new PrintWriter(err, true));
            assertFalse(err.toString().contains("\tat "), "no stack trace: " + err);
            List<String> printed = new ArrayList<>(ShellWords.lines(out.toString(), dir));
            printed.addAll(ShellWords.lines(err.toString(), dir));
            assertEquals(expected, printed.stream().map(GoalsPageTest::untimed).toList(),
                    "goals.md, the session on line " + b.line());
            exits.add(args.get(0) + ": " + exit);
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
