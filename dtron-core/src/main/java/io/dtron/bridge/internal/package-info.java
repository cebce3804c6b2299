/** Not API: the parts of {@link io.dtron.bridge.BusBridge}. */
package io.dtron.bridge.internal;
