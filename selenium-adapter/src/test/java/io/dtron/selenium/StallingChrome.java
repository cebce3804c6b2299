package io.dtron.selenium;

import java.lang.reflect.Method;
import org.openqa.selenium.WebDriver;
import org.openqa.selenium.support.events.EventFiringDecorator;
import org.openqa.selenium.support.events.WebDriverListener;

/**
 * Real headless Chromium whose page loads ({@code get}) are held up in the WebDriver call, as a chromedriver or
 * browser starved on a busy machine holds them: the page itself is served at once.
 */
final class StallingChrome implements WebDriverFactory {
    private final long stallMillis;

    StallingChrome(long stallMillis) {
        this.stallMillis = stallMillis;
    }

    @Override
    public WebDriver create() {
        WebDriver driver = HeadlessChrome.defaults().create();
        return new EventFiringDecorator<WebDriver>(new WebDriverListener() {
            @Override
            public void beforeAnyWebDriverCall(WebDriver d, Method method, Object[] args) {
                if (method.getName().equals("get")) {
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
