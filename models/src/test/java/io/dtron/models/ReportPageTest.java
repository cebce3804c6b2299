package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageSessions;
import io.dtron.testsupport.ShellWords;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The {@code $ java -jar dtron.jar ...} sessions of the report page ({@code report.md}) run as written, in this JVM,
 * in a folder holding the shared {@code LightContr.xml} and {@code .trn}; {@code models/target/classes} is this
 * module's classes. A line {@code ...} stands for any lines, {@code ...} in a line for any text. The real-time
 * session may end INCONCLUSIVE where the page shows PASSED when a busy machine held its threads up past a window of
 * the model (the verdict says so); the page's claims about the files are checked too.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class ReportPageTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    private static final Pattern HELD_UP = Pattern.compile(
            "(?m)^INCONCLUSIVE: .*(input executed too late|more than the reorder window)");

    @Test
    void everySessionPrintsWhatThePageShows(@TempDir Path dir) throws Exception {
        Files.copy(ReportBrowserTest.SHARED.resolve("tron/LightContr.xml"), dir.resolve("LightContr.xml"));
        Files.copy(ReportBrowserTest.SHARED.resolve("tron/LightContr.trn"), dir.resolve("LightContr.trn"));
        DocPage page = DocPage.read("report.md");
        List<String> ran = new ArrayList<>();
        for (PageSessions.Session s : PageSessions.of(page, PageSessions.inFolder(dir, "xml|trn|jsonl|html", ROOT))) {
            PageSessions.Printed run = PageSessions.run(DtronCommand::run, s);
            List<String> args = s.args();
            List<String> lines = s.expected();
            int exit = run.exit();
            String printed = String.join("\n", ShellWords.lines(run.out(), dir)) + "\n";
            boolean realTime = args.get(0).equals("run") && !args.contains("--virtual-time");
            if (realTime && exit == 3 && HELD_UP.matcher(printed).find()) {
                // a busy machine held the run up: the lines up to the verdict are still the page's
                lines = lines.subList(0, lines.indexOf(lines.stream().filter(l -> l.startsWith("PASSED: ")).findFirst()
                        .orElseThrow()));
                printed = printed.substring(0, printed.indexOf("INCONCLUSIVE: "));
                exit = 0;
            }
            assertTrue(pattern(lines).matcher(printed).matches(), "report.md, the session on line " + s.line()
                    + " prints\n" + printed + "\nnot what the page shows:\n" + String.join("\n", lines));
            assertEquals("", run.err(), "report.md line " + s.line());
            ran.add(args.get(0) + " " + exit);
        }
        assertEquals(List.of("run 2", "report 0", "run 0"), ran);
        assertArrayEquals(Files.readAllBytes(dir.resolve("lamp.html")), Files.readAllBytes(dir.resolve("again.html")),
                "again.html is lamp.html, byte for byte");
        assertTrue(Files.readString(dir.resolve("lamp.html")).contains("\"verdict\":{\"verdict\":\"FAILED\""));
        assertTrue(Files.isRegularFile(ROOT.resolve("src/site/resources/images/report-failed-lamp.png")),
                "the page's screenshot");
    }

    /** The lines a session shows as one pattern: a line "..." is any lines, "..." in a line any text. */
    private static Pattern pattern(List<String> lines) {
        StringBuilder regex = new StringBuilder();
        for (String l : lines) {
            if (l.strip().equals("...")) {
                regex.append("(?:[^\\n]*\\n)*?");
                continue;
            }
            String[] parts = l.split(Pattern.quote("..."), -1);
            for (int i = 0; i < parts.length; i++) {
                regex.append(i == 0 ? "" : "[^\\n]*").append(Pattern.quote(parts[i]));
            }
            regex.append("\\n");
        }
        return Pattern.compile(regex.toString());
    }
}
