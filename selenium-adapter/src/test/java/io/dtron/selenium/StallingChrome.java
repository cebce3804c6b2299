package io.dtron.selenium;

import java.lang.reflect.Method;
import org.openqa.selenium.WebDriver;
import org.openqa.selenium.support.events.EventFiringDecorator;
import org.openqa.selenium.support.events.WebDriverListener;

/**
 * Real headless Chromium whose page loads ({@code get}) are held up in the WebDriver call, as a chromedriver or
 * browser starved on a busy machine holds them: the page itself is served at once. Either every load is held
 * up, or only each browser's first, as a browser's first page load (its renderer starting) is on a busy machine.
 */
final class StallingChrome implements WebDriverFactory {
    private final long stallMillis;
    private final boolean firstOnly;

    /** Every page load held up {@code stallMillis}. */
    StallingChrome(long stallMillis) {
        this(stallMillis, false);
    }

    StallingChrome(long stallMillis, boolean firstOnly) {
        this.stallMillis = stallMillis;
        this.firstOnly = firstOnly;
    }

    @Override
    public WebDriver create() {
        WebDriver driver = HeadlessChrome.defaults().create();
        return new EventFiringDecorator<WebDriver>(new WebDriverListener() {
            private boolean loaded;

            @Override
            public void beforeAnyWebDriverCall(WebDriver d, Method method, Object[] args) {
                if (method.getName().equals("get") && !(firstOnly && loaded)) {
                    loaded = true;
                    try {
                        Thread.sleep(stallMillis);
                    } catch (InterruptedException e) {
                        Thread.currentThread().interrupt();
                    }
                }
            }
        }).decorate(driver);
    }
}
