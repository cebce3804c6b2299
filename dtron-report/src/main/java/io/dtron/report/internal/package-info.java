/** The report's internals: its JSON text, the model's drawing, the live view's clients. Not API. */
package io.dtron.report.internal;
