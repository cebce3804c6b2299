/**
 * Runtime verification: a {@link io.dtron.engine.monitor.Monitor} watches every observable channel of a closed model
 * (inputs and outputs alike), tracks the set of symbolic states the model can be in with the events' times, finds
 * a missed deadline when time passes it, and reports what the model did not allow as an
 * {@link io.dtron.engine.monitor.Alarm}. It starts from the initial state, from every state the model can reach
 * (a monitor that joins a running system does not know its history), or from the reachable states a state property
 * names.
 */
package io.dtron.engine.monitor;
