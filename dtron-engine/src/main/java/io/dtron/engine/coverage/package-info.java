/**
 * What a test run covered: {@link io.dtron.engine.coverage.Coverage}, the immutable result (locations, edges,
 * traps, observable channels and their values, measured against what the model checker finds coverable);
 * {@link io.dtron.engine.coverage.RunCoverage}, the live view of a run in progress (for strategies that steer
 * towards what is not covered yet); {@link io.dtron.engine.coverage.StopCondition}, the {@code --until}
 * expressions; {@link io.dtron.engine.coverage.Goals}, the test purposes a stop condition asks about.
 */
package io.dtron.engine.coverage;
