package io.dtron.selenium;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.selenium.internal.BrowserFailure;
import java.net.http.HttpTimeoutException;
import org.junit.jupiter.api.Test;
import org.openqa.selenium.NoSuchElementException;
import org.openqa.selenium.NoSuchSessionException;
import org.openqa.selenium.StaleElementReferenceException;
import org.openqa.selenium.TimeoutException;
import org.openqa.selenium.WebDriverException;

/** Which failures of a step are the adapters' own machinery, and which may be the system under test's. */
class MachineryFailureTest {
    @Test
    void aBrowserThatIsGoneOrDoesNotAnswerIsTheAdaptersOwn() {
        assertTrue(AbstractSeleniumAdapter.isMachinery(new NoSuchSessionException("invalid session id")));
        assertTrue(AbstractSeleniumAdapter.isMachinery(new BrowserFailure("the browser of user 0 did not start",
                null)));
        assertTrue(AbstractSeleniumAdapter.isMachinery(new TimeoutException(new HttpTimeoutException(
                "request timed out"))));
        assertTrue(AbstractSeleniumAdapter.isMachinery(new TimeoutException(
                new java.util.concurrent.TimeoutException())));
        assertTrue(AbstractSeleniumAdapter.isMachinery(new WebDriverException("chrome not reachable")));
        assertTrue(AbstractSeleniumAdapter.isMachinery(new TimeoutException(
                "timeout: Timed out receiving message from renderer: 14.711")));
    }

    @Test
    void whatThePageShowsOrLacksIsNot() {
        assertFalse(AbstractSeleniumAdapter.isMachinery(new AdapterException("the page says 'Hi user0'")));
        assertFalse(AbstractSeleniumAdapter.isMachinery(new NoSuchElementException("no such element")));
        assertFalse(AbstractSeleniumAdapter.isMachinery(new StaleElementReferenceException("stale")));
        assertFalse(AbstractSeleniumAdapter.isMachinery(new TimeoutException(
                "Expected condition failed: waiting for visibility of element located by By.id: done")));
        assertFalse(AbstractSeleniumAdapter.isMachinery(new AssertionError("wrong total")));
    }
}
