/**
 * The monitor's state sets ({@link io.dtron.engine.internal.monitor.Tracker}): interned sets of symbolic states of
 * a closed network, the transitions events take between them, the delays they allow, and the reachable states a
 * monitor without history starts from.
 */
package io.dtron.engine.internal.monitor;
