/** The ticker: a system under test for the bundled model {@code ticker.xml}. */
package io.dtron.models.ticker;
