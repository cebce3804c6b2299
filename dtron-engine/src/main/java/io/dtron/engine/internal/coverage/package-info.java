/** The recording of a run's coverage, behind {@link io.dtron.engine.coverage.RunCoverage}. */
package io.dtron.engine.internal.coverage;
