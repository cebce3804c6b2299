/** Internals of TRON's socket-adapter protocol: frame layouts, a strict frame reader and a serialised writer. */
package io.dtron.tron.internal;
