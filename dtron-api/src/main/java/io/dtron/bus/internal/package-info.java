/**
 * Not API: the JGroups and NATS transports and their helpers. May change without notice.
 */
package io.dtron.bus.internal;
