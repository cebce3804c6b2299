/**
 * Not API: the implementation behind {@code io.dtron.selenium} (finding classes in a package, locators, the
 * browsers and worker threads of the simulated users). May change without notice.
 */
package io.dtron.selenium.internal;
