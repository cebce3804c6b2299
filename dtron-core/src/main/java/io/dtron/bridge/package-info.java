/**
 * The bridge between DTRON's engine and the bus: {@link io.dtron.bridge.BusBridge} is the engine's
 * {@link io.dtron.engine.Adapter} for systems under test whose adapters are members of a DTRON bus.
 */
package io.dtron.bridge;
