package io.dtron.selenium;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.cli.DtronCommand;
import io.dtron.selenium.internal.StepWatch;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.LogCapture;
import io.dtron.testsupport.Waits;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * The adapters' own machinery failing or stalling in real headless Chromium: a step held up in a WebDriver call
 * is logged while it runs with the call and the adapter's line, and given up at the step timeout; a browser that
 * is gone fails no result; either way the adapters leave the bus, so that the tester's verdict is INCONCLUSIVE,
 * never FAILED for a page that did nothing wrong.
 */
@Timeout(value = 90, unit = TimeUnit.SECONDS)
class AdapterMachineryTest {
    private static final IDtronChannel RESULT = IDtronChannel.of("result", "user", "resCode");
    private static final IDtronChannel GREET = IDtronChannel.of("greet", "user");
    private static final IDtronChannel CRASH = IDtronChannel.of("crash", "user");

    /** A tester member and the adapters on a bus of their own. */
    private static final class Bus implements AutoCloseable {
        final TestSite site = new TestSite();
        final Dtron tester;
        final Dtron adapterMember;
        final SeleniumAdapters adapters;
        final Inbox results = new Inbox(RESULT);

        Bus(SeleniumAdapters.Builder builder) throws Exception {
            String cluster = "selenium-" + UUID.randomUUID().toString().substring(0, 8);
            tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build());
            adapterMember = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build());
            tester.addDtronListener(results);
            adapters = builder.property("BASE_URL", site.url()).build();
            adapters.start(adapterMember);
            assertTrue(tester.awaitMembers(2, Duration.ofSeconds(10)));
        }

        /** Waits until the adapters' member has left the bus. */
        void awaitAdaptersLeft() {
            Waits.await("the adapters gave up the run and left the bus")
                    .until(() -> !tester.getMembers().contains(adapterMember.getMemberId()));
        }

        @Override
        public void close() {
            try {
                adapters.close();
            } finally {
                adapterMember.close();
                tester.close();
                site.close();
            }
        }
    }

    @Test
    void aStepHeldUpInAWebDriverCallIsLoggedWhileItRunsAndGivenUpAtTheStepTimeout() throws Exception {
        try (LogCapture watch = new LogCapture(StepWatch.class);
             LogCapture adapters = new LogCapture(SeleniumAdapters.class);
             Bus bus = new Bus(SeleniumAdapters.builder().scan("io.dtron.selenium.sample")
                     .driverFactory(new StallingChrome(15_000)).browsers(1)
                     .property(SeleniumAdapters.SLOW_STEP_PROPERTY, "500")
                     .property(SeleniumAdapters.STEP_TIMEOUT_PROPERTY, "1500"))) {
            long start = System.nanoTime();
            bus.tester.send(GREET.constructValued(Map.of("user", 0)));
            bus.awaitAdaptersLeft();
            long millis = (System.nanoTime() - start) / 1_000_000;
            assertTrue(millis >= 1500 && millis < 6_000, "left after " + millis + " ms");
            assertNull(bus.results.poll(300), "no result blames the page for the adapters' stall");

            List<String> running = watch.messages();
            assertEquals(1, running.size(), running.toString());
            assertTrue(running.get(0).startsWith("Greet[greet[user]] on greet{user=0} for user 0 is still running"
                    + " after "), running.get(0));
            assertTrue(running.get(0).contains(": waiting in the WebDriver call "), running.get(0));
            assertTrue(running.get(0).contains(" at io.dtron.selenium.sample.Greet.execute(Greet.java:"),
                    running.get(0));

            List<String> gaveUp = adapters.messages();
            assertEquals(1, gaveUp.size(), gaveUp.toString());
            assertTrue(gaveUp.get(0).startsWith("Greet[greet[user]] on greet{user=0} for user 0 has run "), gaveUp.get(0));
            assertTrue(gaveUp.get(0).contains(" ms, more than the step timeout of 1500 ms: waiting in the WebDriver"
                    + " call "), gaveUp.get(0));
            assertTrue(gaveUp.get(0).contains("the Selenium adapters stop and leave the bus, so that the run ends"
                    + " INCONCLUSIVE"), gaveUp.get(0));
        }
    }

    @Test
    void aBrowserThatIsGoneReportsNoResultAndTheAdaptersLeave() throws Exception {
        try (LogCapture adapters = new LogCapture(SeleniumAdapters.class);
             Bus bus = new Bus(SeleniumAdapters.builder().scan("io.dtron.selenium.broken").browsers(1))) {
            bus.tester.send(CRASH.constructValued(Map.of("user", 0)));
            bus.awaitAdaptersLeft();
            assertNull(bus.results.poll(300), "no resCode 1 for the browser's failure");
            List<String> gaveUp = adapters.messages();
            assertEquals(1, gaveUp.size(), gaveUp.toString());
            assertTrue(gaveUp.get(0).startsWith("Crash[crash[user]] could not do crash{user=0} for user 0 after "),
                    gaveUp.get(0));
            assertTrue(gaveUp.get(0).contains("NoSuchSessionException"), gaveUp.get(0));
        }
    }

    @Test
    void aStepThatDiesOfAVirtualMachineErrorIsLoggedAndTheAdaptersLeave() throws Exception {
        try (LogCapture adapters = new LogCapture(SeleniumAdapters.class);
             LogCapture sessions = new LogCapture(io.dtron.selenium.internal.UserSessions.class);
             Bus bus = new Bus(SeleniumAdapters.builder().scan("io.dtron.selenium.broken"))) {
            bus.tester.send(IDtronChannel.of("overflow", "user").constructValued(Map.of("user", 1)));
            bus.awaitAdaptersLeft();
            assertNull(bus.results.poll(300));
            assertTrue(adapters.messages().stream().anyMatch(m -> m.startsWith("Overflow[overflow[user]] could not do"
                    + " overflow{user=1} for user 1: java.lang.StackOverflowError: deliberate")),
                    adapters.messages().toString());
            assertTrue(sessions.messages().contains("A step of user 1 ended with an unexpected"
                    + " java.lang.StackOverflowError"), sessions.messages().toString());
        }
    }

    /** The output of a {@code dtron run} of greet.xml in this JVM with an adapter class, and its exit code. */
    private record Run(int exit, String out) {
    }

    private static Run runGreet(String adapter, int timeout) throws Exception {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        try (TestSite site = new TestSite()) {
            System.setProperty("BASE_URL", site.url());
            Path model = Path.of(AdapterMachineryTest.class.getResource("greet.xml").toURI());
            int exit = DtronCommand.run(new String[] {"run", model.toString(), "--adapter", adapter, "--cluster",
                    "selenium-" + UUID.randomUUID().toString().substring(0, 8), "--timeunit", "100000", "--timeout",
                    Integer.toString(timeout), "--delay-policy", "random-bounded", "--delay-bound", "3", "--seed",
                    "1"}, new PrintWriter(out), new PrintWriter(err));
            return new Run(exit, out + "\n" + err);
        } finally {
            System.clearProperty("BASE_URL");
        }
    }

    /**
     * The walkthrough's failure: a browser's first page load, slow on a busy machine, made in the first step counts
     * against the page (greet.xml allows it 5 s) and fails the run although the page did nothing wrong. The log
     * now says where the step's time went while it ran.
     */
    @Test
    void aBrowsersSlowFirstPageLoadInTheFirstStepCountsAgainstThePage() throws Exception {
        try (LogCapture watch = new LogCapture(StepWatch.class)) {
            Run run = runGreet(FirstLoadAdapters.class.getName() + ":cold", 70);
            assertEquals(2, run.exit(), run.out());
            assertTrue(run.out().contains("\nFAILED: no output came by "), run.out());
            assertTrue(watch.messages().stream().anyMatch(m -> m.startsWith("Greet[greet[user]] on greet{user=0} for"
                    + " user 0 is still running after ") && m.contains(": waiting in the WebDriver call ")
                    && m.contains(" at io.dtron.selenium.sample.Greet.execute(Greet.java:")), watch.messages()
                    .toString());
        }
    }

    /** The fix: the start page is the browser's first page load, before the run; the same run passes. */
    @Test
    void withAStartPageTheFirstPageLoadIsDoneBeforeTheRunAndThePagePasses() throws Exception {
        Run run = runGreet(FirstLoadAdapters.class.getName() + ":warm", 70);
        assertEquals(0, run.exit(), run.out());
        assertTrue(run.out().contains("\nPASSED: the timeout of 70 time units was reached"), run.out());
    }

    @Test
    void aRunWhoseStepsStallInTheBrowserIsInconclusiveNotFailed() throws Exception {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        try (LogCapture adapters = new LogCapture(SeleniumAdapters.class); TestSite site = new TestSite()) {
            System.setProperty("BASE_URL", site.url());
            Path model = Path.of(AdapterMachineryTest.class.getResource("greet.xml").toURI());
            int exit = DtronCommand.run(new String[] {"run", model.toString(), "--adapter",
                    StallingAdapters.class.getName(), "--cluster", "selenium-" + UUID.randomUUID().toString()
                    .substring(0, 8), "--timeunit", "100000", "--timeout", "100", "--delay-policy", "random-bounded",
                    "--delay-bound", "3", "--seed", "1"}, new PrintWriter(out), new PrintWriter(err));
            String text = out + "\n" + err;
            assertEquals(3, exit, text);
            assertTrue(text.contains("\nINCONCLUSIVE: "), text);
            assertTrue(text.contains(" left the bus"), text);
            List<String> gaveUp = adapters.messages();
            assertEquals(1, gaveUp.size(), gaveUp.toString());
            assertTrue(gaveUp.get(0).contains("for user 0 has run "), gaveUp.get(0));
            assertTrue(gaveUp.get(0).contains("more than the step timeout of " + StallingAdapters.STEP_TIMEOUT_MILLIS
                    + " ms: waiting in the WebDriver call "), gaveUp.get(0));
        } finally {
            System.clearProperty("BASE_URL");
        }
    }
}
