/**
 * Not API: implementations behind {@code io.dtron.api} (channel templates and
 * values, the {@code Sync} codec, counters, listener dispatch). May change
 * without notice.
 */
package io.dtron.api.internal;
