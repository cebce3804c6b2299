/**
  * Not API. Zones over clocks as difference bound matrices (DBMs), the symbolic representation of clock
  * valuations used by the engine (the tester, the verifier, the monitor and the controller).
  *
  * <p>{@link io.dtron.engine.internal.zone.Bound} encodes one bound on a clock difference as a raw
  * {@code int}; {@link io.dtron.engine.internal.zone.Dbm} is a mutable zone kept in canonical form; {@link
  * io.dtron.engine.internal.zone.Relation} is the result of comparing two zones.
  */
package io.dtron.engine.internal.zone;
