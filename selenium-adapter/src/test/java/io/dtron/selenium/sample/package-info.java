/** Adapters of the tests' small web site, found by scanning this package. */
package io.dtron.selenium.sample;
