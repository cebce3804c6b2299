/**
 * Selenium adapters: test a web application against a DTRON model, one browser per simulated user.
 *
 * <p>An adapter is a class extending {@link io.dtron.selenium.AbstractSeleniumAdapter}; it serves the model
 * input named after the class ({@code Login} serves {@code i_login}) and answers every message with the output
 * {@code o_result}, whose {@code resCode} is 0 when {@link io.dtron.selenium.AbstractSeleniumAdapter#execute
 * execute} returns and 1 when it throws, unless the adapter reports its own code. When the input carries a
 * variable {@code user}, the message is run in that user's browser and the result carries the same {@code user}.
 * {@link io.dtron.selenium.SeleniumAdapters} finds the adapters of a package, creates them with Guice
 * ({@code @Inject @Named("KEY")} values come from the package's {@code adapters.properties}) and starts them
 * on a bus; {@link io.dtron.selenium.HeadlessChrome} starts the browsers.
 */
package io.dtron.selenium;
