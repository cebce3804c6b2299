package io.dtron.selenium;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.openqa.selenium.HasCapabilities;
import org.openqa.selenium.WebDriver;

/** Headless Chromium from Debian's packages, on loopback. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class HeadlessChromeTest {

    @Test
    void startsChromiumWithAFreshProfileThatQuittingDeletes() throws Exception {
        HeadlessChrome chrome = HeadlessChrome.builder().implicitWait(Duration.ofMillis(500)).build();
        Path profile;
        try (TestSite site = new TestSite()) {
            WebDriver driver = chrome.create();
            try {
                Map<?, ?> chromeCapabilities = (Map<?, ?>) ((HasCapabilities) driver).getCapabilities()
                        .getCapability("chrome");
                profile = Path.of((String) chromeCapabilities.get("userDataDir"));
                assertTrue(profile.getFileName().toString().startsWith("dtron-chromium-"), profile.toString());
                assertTrue(Files.isDirectory(profile));
                assertEquals(Duration.ofMillis(500), driver.manage().timeouts().getImplicitWaitTimeout());
                driver.get(site.url() + "/form");
                assertEquals("Form", driver.getTitle());
            } finally {
                driver.quit();
            }
        }
        assertFalse(Files.exists(profile), "quitting deletes " + profile);
    }

    @Test
    void aMissingBrowserSaysWhatToInstall() {
        HeadlessChrome chrome = HeadlessChrome.builder().chromium(Path.of("/nonexistent/chromium")).build();
        AdapterException e = assertThrows(AdapterException.class, chrome::create);
        assertEquals("no Chromium at /nonexistent/chromium: install Debian's chromium and chromium-driver"
                + " (apt-get install chromium chromium-driver), or give its path", e.getMessage());
    }
}
