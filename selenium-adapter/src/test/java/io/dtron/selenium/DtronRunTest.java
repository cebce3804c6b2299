package io.dtron.selenium;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.LogCapture;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.URISyntaxException;
import java.nio.file.Path;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * {@code dtron run MODEL --adapter io.dtron.selenium.SeleniumAdapters:io.dtron.selenium.sample}: the tester and the
 * sample adapters on a bus in this JVM, against the tests' small web site in headless Chromium. The site's address
 * reaches the adapters as a system property named like the key of {@code adapters.properties}.
 */
@Timeout(value = 90, unit = TimeUnit.SECONDS)
class DtronRunTest {
    private static final String ADAPTERS = SeleniumAdapters.class.getName() + ":io.dtron.selenium.sample";

    /** The output and exit code of one run. */
    private record Run(int exit, String out) {
    }

    private static Run run(String model, int timeout) throws Exception {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        try (TestSite site = new TestSite()) {
            System.setProperty("BASE_URL", site.url());
            int exit = DtronCommand.run(new String[] {"run", resource(model).toString(), "--adapter", ADAPTERS,
                    "--cluster", "selenium-" + UUID.randomUUID().toString().substring(0, 8), "--timeunit", "100000",
                    "--timeout", Integer.toString(timeout), "--delay-policy", "random-bounded", "--delay-bound", "3",
                    "--seed", "1"}, new PrintWriter(out), new PrintWriter(err));
            return new Run(exit, out + "\n" + err);
        } finally {
            System.clearProperty("BASE_URL");
        }
    }

    private static Path resource(String name) throws URISyntaxException {
        return Path.of(DtronRunTest.class.getResource(name).toURI());
    }

    @Test
    void aWebTestOfTheSampleSitePasses() throws Exception {
        Run run = run("greet.xml", 50);
        assertEquals(0, run.exit(), run.out());
        Matcher passed = Pattern.compile("\nPASSED: the timeout of 50 time units was reached after (\\d+) inputs? and"
                + " (\\d+) outputs?").matcher(run.out());
        assertTrue(passed.find(), run.out());
        // how many greetings fit is the browser's business (the model gives the site up to 5 s to answer); what the
        // model fixes: greetings and results alternate, the last greeting's result may be on its way
        int inputs = Integer.parseInt(passed.group(1));
        int outputs = Integer.parseInt(passed.group(2));
        assertTrue(inputs >= 1 && (outputs == inputs || outputs == inputs - 1), run.out());
    }

    @Test
    void aWrongLocatorFailsTheRunAtOnceAndTheLogNamesIt() throws Exception {
        try (LogCapture log = new LogCapture(AbstractSeleniumAdapter.class)) {
            Run run = run("press.xml", 300);
            assertEquals(2, run.exit(), run.out());
            assertTrue(Pattern.compile("\nFAILED: (?:[^\n]*?; then )?output result\\(user=0, resCode=1\\) observed at"
                    + " t=[0-9.]+ carries"
                    + " values the model does not allow then: it allowed result\\(user=0, resCode=0\\)")
                    .matcher(run.out()).find(), run.out());
            // at once: the verdict is the first result's (the run's 30 s are not waited out), whatever the wall
            // clock, which a busy machine's Chromium stretches, says
            List<String> messages = log.messages();
            assertTrue(messages.stream().anyMatch(m -> m.startsWith("Press[press[user]] failed on press{user=0}")
                    && m.contains("no element MISSING_BUTTON (id:no-such-button) on http://127.0.0.1:")),
                    messages.toString());
        }
    }
}
