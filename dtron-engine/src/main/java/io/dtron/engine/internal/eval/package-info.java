/**
 * The evaluator of a network's intermediate representation: data expressions and function bodies over the
 * integer state vector, clock resets from updates, channel numbers of synchronisations, and guards and
 * invariants applied to zones. Not public API; the engine uses {@link io.dtron.engine.internal.eval.Evaluator},
 * {@link io.dtron.engine.internal.eval.ClockResets}, {@link io.dtron.engine.internal.eval.ClockBounds} and
 * {@link io.dtron.engine.internal.eval.ModelRuntimeException}.
 *
 * <p>Each expression is compiled once into a tree of small node objects; function frames live on one growable
 * integer stack, so that evaluation allocates nothing.
 */
package io.dtron.engine.internal.eval;
