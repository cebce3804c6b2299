/**
 * Sample systems under test for the sample models. Each in-process system is an {@link io.dtron.engine.Adapter}
 * with a public no-argument constructor (the correct system) and one taking a variant name (a faulty variant), as
 * {@code dtron run --sut CLASS[:VARIANT]} expects; a bus adapter ({@link io.dtron.api.DtronAdapter}, such as
 * {@link io.dtron.models.ticker.TickerBusAdapter}) has the same constructors, for
 * {@code dtron run --adapter CLASS[:VARIANT]}.
 */
package io.dtron.models;
