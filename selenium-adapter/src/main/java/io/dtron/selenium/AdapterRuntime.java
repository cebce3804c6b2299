package io.dtron.selenium;

import io.dtron.api.Dtron;
import io.dtron.selenium.internal.Locators;
import io.dtron.selenium.internal.UserSessions;

/**
 * What the adapters of one {@link SeleniumAdapters} share while they run: the bus member, the users' browsers
 * and worker threads, and the locators.
 *
 * @param dtron    the bus member the adapters listen and report on
 * @param sessions the simulated users
 * @param locators the locators of the adapters' properties
 */
record AdapterRuntime(Dtron dtron, UserSessions sessions, Locators locators) {
}
