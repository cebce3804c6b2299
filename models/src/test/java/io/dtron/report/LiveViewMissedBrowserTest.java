package io.dtron.report;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.model.Layout;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.models.lamp.SmartLamp;
import io.dtron.selenium.HeadlessChrome;
import io.dtron.testsupport.Waits;
import java.net.InetAddress;
import java.nio.file.Path;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.openqa.selenium.By;
import org.openqa.selenium.WebDriver;
import org.openqa.selenium.WebElement;

/**
 * The live page in real headless Chromium when it cannot keep up: a browser's queue of one update overflows as a
 * virtual-time run of the lamp goes as fast as the CPU allows; the page says that it missed updates, fetches the
 * whole state again, and ends showing every event of the run and its verdict. (In this package for the live view's
 * queue size, which only tests set.)
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class LiveViewMissedBrowserTest {
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");

    @Test
    void aPageThatMissedUpdatesSaysSoAndFetchesTheWholeStateAgain() throws Exception {
        Path model = SHARED.resolve("tron/LightContr.xml");
        Network network = ModelLoader.load(model);
        TestInterface lamp = TestInterface.fromFile(network, SHARED.resolve("tron/LightContr.trn"));
        RunRecord record = new RunRecord(model.toString(), network, Layout.read(model), null);
        WebDriver browser = HeadlessChrome.defaults().create();
        try (LiveView live = LiveView.start(record, InetAddress.getLoopbackAddress(), 0, 1)) {
            browser.get(live.url());
            WebElement body = browser.findElement(By.tagName("body"));
            Waits.await("the page follows the run").until(() -> live.browsers() == 1
                    && "true".equals(body.getAttribute("data-ready")));
            TestOptions options = TestOptions.defaults(9).withTimeout(100_000);
            OnlineTester tester = new OnlineTester(network, lamp, new SmartLamp(), options);
            record.start(options.seed(), options.timeUnitMicros(), options.timeout(), options.virtualTime());
            tester.addListener(new RunRecorder(record));
            TestResult result = tester.run();
            assertTrue(live.droppedUpdates() > 0, "a queue of one update overflowed");
            Waits.await("the page shows the whole run").until(() -> result.verdict().name().equals(body.getAttribute(
                    "data-verdict")) && Integer.toString(record.eventCount()).equals(body.getAttribute(
                    "data-events")));
            assertTrue(Integer.parseInt(body.getAttribute("data-missed")) >= 1, "the page was told it missed some");
            assertTrue(browser.findElement(By.id("live-note")).getText().startsWith("live: this page missed updates"
                    + " (it did not keep up) and fetched the whole state again"), browser.findElement(By.id(
                    "live-note")).getText());
            assertEquals(result.inputs() + result.outputs(), record.eventCount());
        } finally {
            browser.quit();
        }
    }
}
