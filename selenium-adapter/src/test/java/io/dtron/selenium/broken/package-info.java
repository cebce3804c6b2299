/** An adapter whose browser fails under it, for the tests of the adapters' own failures. */
package io.dtron.selenium.broken;
