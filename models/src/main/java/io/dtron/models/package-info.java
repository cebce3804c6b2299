/**
 * Sample systems under test for the sample models. Each is an {@link io.dtron.engine.Adapter} with a public
 * no-argument constructor (the correct system) and one taking a variant name (a faulty variant), as
 * {@code dtron run --sut CLASS[:VARIANT]} expects.
 */
package io.dtron.models;
