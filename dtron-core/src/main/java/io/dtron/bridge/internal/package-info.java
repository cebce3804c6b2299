/** Not API: the parts of {@link io.dtron.bridge.BusRun}. */
package io.dtron.bridge.internal;
