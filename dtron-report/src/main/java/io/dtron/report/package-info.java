/**
 * The report of a run: {@link io.dtron.report.RunRecord}, what a run did (filled by a
 * {@link io.dtron.report.RunRecorder} or from a trace); {@link io.dtron.report.ReportPage}, the self-contained HTML
 * page drawing it (the model from its saved layout, coverage, the inputs and outputs, delays); {@link
 * io.dtron.report.LiveView}, the page served while the run goes on.
 */
package io.dtron.report;
