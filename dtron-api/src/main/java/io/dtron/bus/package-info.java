/**
 * The bus under DTRON: a small service-provider interface for publish/subscribe
 * transports that deliver every message to every member in one total order.
 *
 * <p>A {@link io.dtron.bus.Transport} carries opaque payloads on named groups
 * (one group per channel) and reports {@link io.dtron.bus.MembershipView
 * membership views}. The default transport is JGroups; users normally reach
 * it through {@link io.dtron.api.Dtron} rather than directly.
 */
package io.dtron.bus;
