package io.dtron.selenium;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.LogCapture;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestInstance;
import org.junit.jupiter.api.Timeout;

/**
 * The sample adapters in two real headless Chromium browsers, on an in-JVM bus: a test member plays the tester,
 * sends inputs and takes the results.
 */
@TestInstance(TestInstance.Lifecycle.PER_CLASS)
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class AdapterResultsTest {
    private static final IDtronChannel RESULT = IDtronChannel.of("result", "user", "resCode");
    private static final IDtronChannel GREET = IDtronChannel.of("greet", "user");
    private static final IDtronChannel FAREWELL = IDtronChannel.of("farewell", "user");
    private static final IDtronChannel REMEMBER = IDtronChannel.of("remember", "user", "value");
    private static final IDtronChannel RECALL = IDtronChannel.of("recall", "user");
    private static final IDtronChannel PRESS = IDtronChannel.of("press", "user");

    private TestSite site;
    private Dtron tester;
    private Dtron adapterMember;
    private SeleniumAdapters adapters;
    private final Inbox results = new Inbox(RESULT);

    @BeforeAll
    void start() throws Exception {
        site = new TestSite();
        String cluster = "selenium-" + UUID.randomUUID().toString().substring(0, 8);
        tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build());
        adapterMember = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build());
        tester.addDtronListener(results);
        adapters = SeleniumAdapters.builder().scan("io.dtron.selenium.sample").property("BASE_URL", site.url())
                .browsers(2).build();
        adapters.start(adapterMember);
        assertTrue(tester.awaitMembers(2, Duration.ofSeconds(10)));
    }

    @AfterAll
    void stop() {
        try {
            if (adapters != null) {
                adapters.close();
            }
        } finally {
            if (adapterMember != null) {
                adapterMember.close();
            }
            if (tester != null) {
                tester.close();
            }
            if (site != null) {
                site.close();
            }
        }
    }

    @Test
    void aStepThatReturnsReportsResultCodeZeroForItsUser() throws Exception {
        tester.send(GREET.constructValued(Map.of("user", 1)));
        assertEquals(Map.of("user", 1, "resCode", 0), results.take().getVariables());
        tester.send(FAREWELL.constructValued(Map.of("user", 1)));
        assertEquals(Map.of("user", 1, "resCode", 0), results.take().getVariables(),
                "Farewell checked Greet's post-condition in user 1's browser");
        assertNull(results.poll(300), "one result per message");
    }

    @Test
    void anAdapterThatReportsItsOwnCodeGetsNoAutomaticOne() throws Exception {
        tester.send(REMEMBER.constructValued(Map.of("user", 0, "value", 42)));
        assertEquals(Map.of("user", 0, "resCode", 0), results.take().getVariables());
        tester.send(RECALL.constructValued(Map.of("user", 0)));
        assertEquals(Map.of("user", 0, "resCode", 42), results.take().getVariables());
        assertNull(results.poll(300), "no automatic result after the adapter's own");
    }

    @Test
    void eachUserHasABrowserOfItsOwnAndUsersRunInParallel() throws Exception {
        tester.send(REMEMBER.constructValued(Map.of("user", 0, "value", 7)));
        tester.send(REMEMBER.constructValued(Map.of("user", 1, "value", 9)));
        tester.send(RECALL.constructValued(Map.of("user", 0)));
        tester.send(RECALL.constructValued(Map.of("user", 1)));
        List<Map<String, Integer>> got = List.of(results.take().getVariables(), results.take().getVariables(),
                results.take().getVariables(), results.take().getVariables());
        assertTrue(got.contains(Map.of("user", 0, "resCode", 7)), got.toString());
        assertTrue(got.contains(Map.of("user", 1, "resCode", 9)), got.toString());
        assertTrue(got.indexOf(Map.of("user", 0, "resCode", 0)) < got.indexOf(Map.of("user", 0, "resCode", 7)),
                "a user's results come in the order of its messages: " + got);
    }

    @Test
    void aWrongLocatorFailsFastWithResultCodeOneAndTheLocatorInTheLog() throws Exception {
        try (LogCapture log = new LogCapture(AbstractSeleniumAdapter.class)) {
            long start = System.nanoTime();
            tester.send(PRESS.constructValued(Map.of("user", 0)));
            IDtronChannelValued result = results.take();
            long millis = (System.nanoTime() - start) / 1_000_000;
            assertEquals(Map.of("user", 0, "resCode", AbstractSeleniumAdapter.RESULT_FAILED), result.getVariables());
            // fast: after the locator's wait of 2 s (the log says so below), not before; a busy machine may add to it
            assertTrue(millis >= 2000, "failed after " + millis + " ms");
            List<String> messages = log.messages();
            assertEquals(1, messages.size(), messages.toString());
            String message = messages.get(0);
            assertTrue(message.startsWith("Press[press[user]] failed on press{user=0} for user 0 after "), message);
            assertTrue(message.contains(", reporting resCode 1: no element MISSING_BUTTON (id:no-such-button) on "
                    + site.url() + "/form (\"Form\") within 2000 ms"), message);
            assertFalse(log.anyStackTrace(), "an expected failure is logged without a stack trace");
        }
    }

    @Test
    void findInputFindsFieldsByTheirLabels() throws Exception {
        tester.send(GREET.constructValued(Map.of("user", 0)));
        assertEquals(Map.of("user", 0, "resCode", 0), results.take().getVariables(),
                "'Your name' found the field of <label for=name>Your  name</label>");
    }
}
