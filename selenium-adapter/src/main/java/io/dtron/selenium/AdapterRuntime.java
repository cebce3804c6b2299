package io.dtron.selenium;

import io.dtron.api.Dtron;
import io.dtron.selenium.internal.Locators;
import io.dtron.selenium.internal.UserSessions;
import java.util.function.BooleanSupplier;
import java.util.function.Consumer;

/**
 * What the adapters of one {@link SeleniumAdapters} share while they run: the bus member, the users' browsers
 * and worker threads, the locators, and the way out when the adapters' own machinery fails.
 *
 * @param dtron    the bus member the adapters listen and report on
 * @param sessions the simulated users
 * @param locators the locators of the adapters' properties
 * @param giveUp   called with the reason when a step cannot be done because of the adapters' own machinery (a
 *                 browser that does not start or answer): the adapters leave the bus, so that the tester ends
 *                 the run INCONCLUSIVE instead of blaming the system under test
 * @param gaveUp   whether the adapters gave up: a step that ends after that reports nothing
 */
record AdapterRuntime(Dtron dtron, UserSessions sessions, Locators locators, Consumer<String> giveUp,
                      BooleanSupplier gaveUp) {
}
