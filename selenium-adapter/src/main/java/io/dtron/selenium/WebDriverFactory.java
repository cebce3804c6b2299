package io.dtron.selenium;

import org.openqa.selenium.WebDriver;

/** Starts the browser of one simulated user. {@link HeadlessChrome} is the default. */
@FunctionalInterface
public interface WebDriverFactory {

    /**
     * Starts a browser; {@link WebDriver#quit()} must stop it and release everything it holds.
     *
     * @throws AdapterException if the browser cannot be started, saying why
     */
    WebDriver create();
}
