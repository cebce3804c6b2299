package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageSessions;
import io.dtron.testsupport.ShellWords;
import java.io.File;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The {@code $ java -jar dtron.jar ...} sessions of the coverage page ({@code coverage.md}) run as written, in order,
 * in this JVM, in one folder holding the shared {@code LightContr.xml} and {@code .trn} and the bundled
 * {@code ticker.xml}: every run is in virtual time, so each prints exactly what the page shows (standard output,
 * then standard error), and the files the page describes hold what it says.
 */
class CoveragePageTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");

    @Test
    void everySessionPrintsWhatThePageShowsAndTheFilesHoldWhatItSays(@TempDir Path dir) throws Exception {
        Files.copy(SHARED.resolve("tron/LightContr.xml"), dir.resolve("LightContr.xml"));
        Files.copy(SHARED.resolve("tron/LightContr.trn"), dir.resolve("LightContr.trn"));
        Files.copy(ROOT.resolve("models/src/main/resources/io/dtron/models/ticker.xml"), dir.resolve("ticker.xml"));
        DocPage page = DocPage.read("coverage.md");
        List<String> exits = new ArrayList<>();
        for (PageSessions.Session s : PageSessions.of(page, PageSessions.inFolder(dir, "xml|trn|json|jsonl", ROOT))) {
            PageSessions.Printed run = PageSessions.run(DtronCommand::run, s);
            List<String> printed = new ArrayList<>(ShellWords.lines(run.out(), dir));
            printed.addAll(ShellWords.lines(run.err(), dir));
            assertEquals(s.expected(), printed, "coverage.md, the session " + s.command() + " in the block on line "
                    + s.line());
            exits.add(String.join(" ", s.args().subList(0, 2)).replace(dir + File.separator, "") + ": " + run.exit());
        }
        assertEquals(List.of("run LightContr.xml: 0", "run LightContr.xml: 0", "coverage merge: 0", "run ticker.xml: 0",
                "coverage merge: 1", "run LightContr.xml: 0", "run LightContr.xml: 1"), exits);

        // the keys of the file are those of the page's table; the switch's edge and the output channel as shown
        String one = Files.readString(dir.resolve("lamp-1.json"));
        Matcher key = Pattern.compile("(?m)^  \"(\\w+)\":").matcher(one);
        List<String> keys = new ArrayList<>();
        while (key.find()) {
            keys.add(key.group(1));
        }
        List<String> table = new ArrayList<>();
        Matcher row = Pattern.compile("(?m)^\\| `(\\w+)` \\| ").matcher(page.text().substring(
                page.text().indexOf("| key | what it holds |")));
        while (row.find() && !row.group(1).equals("edge_coverage")) {
            table.add(row.group(1));
        }
        assertEquals(table, keys);
        String text = page.text().replaceAll("\\s+", " ");
        String edge = "{\"index\": 1, \"source\": \"idle\", \"target\": \"goingOff\", \"label\": \"touch?\", \"line\": 32,"
                + " \"reach\": \"reachable\", \"taken\": \"no\"}";
        assertTrue(text.contains("An edge of the lamp's switch reads `" + edge + "`"), "the page shows " + edge);
        assertTrue(one.contains(edge), one);
        assertTrue(text.contains("{\"name\": \"level\", \"direction\": \"output\", \"count\": 15, \"values\":"
                + " [{\"adapLevel\": 0}, ...], \"more_values\": false}"), "the page shows the channel level");
        assertTrue(one.contains("{\"name\": \"level\", \"direction\": \"output\", \"count\": 15, \"values\":"
                + " [{\"adapLevel\": 0}, {\"adapLevel\": 1}, {\"adapLevel\": 2}, {\"adapLevel\": 3}, {\"adapLevel\": 4},"
                + " {\"adapLevel\": 5}, {\"adapLevel\": 6}], \"more_values\": false}"), one);
        // the trace's first input and its edges, as the page shows them
        List<String> trace = Files.readAllLines(dir.resolve("lamp-2.jsonl"));
        assertEquals(page.blocks("json").get(0).strip(), String.join("\n", trace.subList(1, 3)));
    }
}
