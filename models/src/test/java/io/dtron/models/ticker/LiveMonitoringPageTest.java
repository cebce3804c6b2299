package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.ShellWords;
import io.dtron.testsupport.Waits;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * The live sessions of the monitoring page ({@code monitoring.md}, "Live, on a bus") run as written, from the
 * project's root: the monitor, then the slow ticker's run on the same bus; the monitor of two runs, then the correct
 * ticker's run and the slow one's. The monitor prints the page's lines but for the member and run ids (and the bus's
 * name, unique to the test), how many ticks a correct run had time for, how many ticks came stamped after its end
 * (between the tester's timeout and its stop), the notes of a reorder window widened (a message that took more
 * than half of it, which a busy machine makes), and the progress lines of a watch that lasts five seconds or more (a
 * busy machine's again). A correct run that PASSED shows no violation.
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class LiveMonitoringPageTest {
    private static final String COMMAND = "$ java -jar dtron-cli/target/dtron.jar ";

    /** The words of a command line of the page, run from this module's folder. */
    private static List<String> args(String line, String cluster) {
        assertTrue(line.startsWith(COMMAND), line);
        List<String> args = new ArrayList<>();
        for (String word : ShellWords.split(line.substring(COMMAND.length()))) {
            args.add(word.equals("demo") ? cluster : word.startsWith("models/") ? "../" + word : word);
        }
        return args;
    }

    private static List<String> normalised(String text, String cluster) {
        return text.replace("../models/", "models/").replace("'" + cluster + "'", "'demo'")
                .replaceAll("dtron-\\d+-[0-9a-f]+", "dtron-ID").replaceAll("run [0-9a-f]+\\b", "run ID")
                .replaceAll("\\d+ events checked", "N events checked")
                .replaceAll(", \\d+ after the run's end \\(not judged\\)", "").lines()
                .filter(line -> !line.startsWith("dtron monitor: reorder window widened")
                        && !line.startsWith("progress: ")).toList();
    }

    @Test
    void theMonitorBesideTheSlowTickerPrintsWhatThePageShows() throws Exception {
        DocPage page = DocPage.read("monitoring.md");
        String cluster = "demo-" + UUID.randomUUID().toString().substring(0, 8);
        List<String> monitorArgs = args(page.blockAfter("first the monitor:").code().strip(), cluster);
        List<String> runArgs = args(page.blockAfter("in another terminal, the run:").code().strip(), cluster);
        String shown = page.blockAfter("with no event (member and run ids").code();
        LiveMonitorTest.Command monitor = new LiveMonitorTest.Command(monitorArgs);
        Waits.await("the monitor on the bus").until(() -> monitor.out.toString().contains(" as ")
                || monitor.result.isDone());
        LiveMonitorTest.Result run = new LiveMonitorTest.Command(runArgs).get();
        LiveMonitorTest.Result watched = monitor.get();
        assertEquals(2, run.exit(), run.shown());
        assertEquals(2, watched.exit(), watched.shown());
        assertEquals(normalised(shown, cluster), normalised(watched.out(), cluster));
    }

    @Test
    void theMonitorOfTwoRunsPrintsWhatThePageShows() throws Exception {
        DocPage page = DocPage.read("monitoring.md");
        String cluster = "runs-" + UUID.randomUUID().toString().substring(0, 8);
        List<String> monitorArgs = args(page.blockAfter("The monitor for two runs, from").code().strip(), cluster);
        List<String> runs = page.blockAfter("the correct ticker's run and, when it has ended").code().strip().lines()
                .toList();
        assertEquals(2, runs.size(), runs.toString());
        String shown = page.blockAfter("how many ticks the correct run had time for").code();
        LiveMonitorTest.Command monitor = new LiveMonitorTest.Command(monitorArgs);
        Waits.await("the monitor on the bus").until(() -> monitor.out.toString().contains(" as ")
                || monitor.result.isDone());
        LiveMonitorTest.Result correct = new LiveMonitorTest.Command(args(runs.get(0), cluster)).get();
        LiveMonitorTest.Result slow = new LiveMonitorTest.Command(args(runs.get(1), cluster)).get();
        LiveMonitorTest.Result watched = monitor.get();
        String all = watched.shown() + correct.shown() + slow.shown();
        assertEquals(2, slow.exit(), all);
        assertEquals(2, watched.exit(), all);
        List<String> expected = normalised(shown, cluster);
        List<String> printed = normalised(watched.out(), cluster);
        int p = printed.lastIndexOf(expected.get(1));
        assertTrue(p > 1, all);
        if (correct.exit() == 0) {
            LiveMonitorTest.agreesWithAPassedRun(String.join("\n", printed.subList(0, p)), all);
            assertEquals(expected, printed, all);
        } else {
            // a correct run that did not PASS on a busy machine: the slow run's lines still are the page's
            int e = expected.lastIndexOf(expected.get(1));
            assertEquals(expected.subList(e, expected.size() - 1), printed.subList(p, Math.min(printed.size(),
                    p + expected.size() - 1 - e)), all);
        }
    }
}
