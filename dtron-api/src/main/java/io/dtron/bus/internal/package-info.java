/**
 * Not API: the JGroups transport and its helpers. May change without notice.
 */
package io.dtron.bus.internal;
