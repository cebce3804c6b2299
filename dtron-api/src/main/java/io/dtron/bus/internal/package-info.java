/**
 * Not API: the bus under DTRON, a {@link io.dtron.bus.internal.Transport} that delivers every message to every member
 * in one total order (its messages, subscriptions and membership views), the JGroups and NATS transports and their
 * helpers. Users reach it through {@link io.dtron.api.Dtron}. May change without notice.
 */
package io.dtron.bus.internal;
