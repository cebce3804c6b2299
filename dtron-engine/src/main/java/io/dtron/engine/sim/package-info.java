/**
 * A model's implementation part as the system under test ({@link io.dtron.engine.sim.ModelSystem}), in the
 * tester's process and in virtual time, and mutation analysis with it ({@link io.dtron.engine.sim.Mutants}): mutants
 * of the implementation part run against the model, and which of them the tester kills.
 */
package io.dtron.engine.sim;
