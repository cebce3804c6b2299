/**
 * The ticker, for the bundled model {@code ticker.xml}: a system under test in the tester's JVM
 * ({@link io.dtron.models.ticker.TickerSystem}) and the same ticker as a bus adapter
 * ({@link io.dtron.models.ticker.TickerBusAdapter}).
 */
package io.dtron.models.ticker;
