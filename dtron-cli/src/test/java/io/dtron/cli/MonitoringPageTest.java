package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageSessions;
import io.dtron.testsupport.ShellWords;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The sessions of the monitoring page ({@code monitoring.md}) run as written, in a folder with the page's files
 * ({@code server.xta}, the monitor tests' model, {@code log.csv}, {@code midway.csv}): every line the page shows is
 * printed, in its order, but for the wall time of a replay ({@code in 0.05 s}).
 */
class MonitoringPageTest {

    @Test
    void theSessionsPrintWhatThePageShows(@TempDir Path dir) throws Exception {
        DocPage page = DocPage.read("monitoring.md");
        String model = page.blockAfter("The server, `server.xta`:").code();
        assertEquals(Files.readString(MonitorCommandTest.SERVER, StandardCharsets.UTF_8), model,
                "the page's server is the monitor tests'");
        Files.writeString(dir.resolve("server.xta"), model);
        Files.writeString(dir.resolve("log.csv"), page.blockAfter("A log of a real server, `log.csv`").code());
        Files.writeString(dir.resolve("midway.csv"), page.blockAfter("`midway.csv` starts with").code());
        List<String> expected = new ArrayList<>();
        List<String> printed = new ArrayList<>();
        int sessions = 0;
        for (PageSessions.Session s : PageSessions.of(page, word -> word.matches("[a-z]+\\.(xta|csv|jsonl)")
                ? dir.resolve(word).toString() : word)) {
            s.expected().forEach(line -> expected.add(line.replaceAll("in \\d+\\.\\d\\d s$", "in (time) s")));
            sessions++;
            PageSessions.Printed r = PageSessions.run(DtronCommand::run, s);
            assertEquals(r.out().contains("violation 1 at") ? 2 : 0, r.exit(), s.command() + "\n" + r.out() + r.err());
            for (String out : ShellWords.lines(r.out(), dir)) {
                printed.add(out.replaceAll("in \\d+\\.\\d\\d s$", "in (time) s"));
            }
        }
        assertEquals(5, sessions, "record, replay, a log with faults, --continue, --from any");
        assertEquals(expected, printed);
    }
}
