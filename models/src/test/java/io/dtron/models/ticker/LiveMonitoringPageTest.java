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
 * The live session of the monitoring page ({@code monitoring.md}, "Live, on a bus") runs as written, from the
 * project's root: the monitor, then the slow ticker's run on the same bus; the monitor prints the page's lines but
 * for the member and run ids (and the bus's name, unique to the test).
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
                .replaceAll("dtron-\\d+-[0-9a-f]+", "dtron-ID").replaceAll("run [0-9a-f]+ started", "run ID started")
                .lines().toList();
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
}
