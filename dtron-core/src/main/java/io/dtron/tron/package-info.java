/**
 * Uppaal TRON's socket-adapter protocol, both sides.
 *
 * <ul>
 *   <li>{@link io.dtron.tron.TronSocketAdapter}: DTRON in TRON's place, the tester's side; its configuration phase
 *       defines the test interface, and it is the {@link io.dtron.engine.Adapter} of the run
 *       ({@code dtron tron} and {@code dtron run --tron-adapter} on the command line).</li>
 *   <li>{@link io.dtron.tron.TronAdapterClient}: the system under test's side, shaped like TRON's Java reporter and
 *       adapter.</li>
 *   <li>{@link io.dtron.tron.TronClockServer}: TRON's virtual clock server ({@code -Q PORT}), for adapters whose
 *       threads are TRON's virtual threads.</li>
 *   <li>{@link io.dtron.tron.TronBackend}: an installed TRON as DTRON's backend, through the client.</li>
 * </ul>
 *
 * <p>Time: real time, TRON's virtual-time acknowledgements (with or without TRON's virtual clock server), or DTRON's
 * shared virtual clock (an extension an adapter asks for); see {@link io.dtron.tron.TronSocketAdapter} and the site page {@code tron.md}.
 */
package io.dtron.tron;
