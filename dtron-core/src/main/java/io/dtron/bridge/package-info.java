/**
 * A run on a DTRON bus and the engine's side of it: {@link io.dtron.bridge.BusRun} owns the run (handshake, run id,
 * time 0, clock offsets, event times, reorder window, delays, membership, end) for whichever role runs the model;
 * {@link io.dtron.bridge.BusBridge} is the tester's side, the engine's {@link io.dtron.engine.Adapter} for systems
 * under test whose adapters are members of the bus.
 */
package io.dtron.bridge;
