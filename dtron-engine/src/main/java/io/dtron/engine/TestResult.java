package io.dtron.engine;

/**
 * The result of a test run.
 *
 * @param verdict      passed, failed or inconclusive
 * @param explanation  why: for a failure, the observation, when, what the model allowed then and the process,
 *                     location and edge involved
 * @param seed         the run's seed
 * @param inputs       the number of inputs applied
 * @param outputs      the number of outputs observed
 * @param durationMicros the test time at the verdict, in microseconds
 * @param coverage     what the run covered, or null when the run was not made by DTRON's engine (TRON)
 */
public record TestResult(Verdict verdict, String explanation, long seed, int inputs, int outputs,
                         long durationMicros, io.dtron.engine.coverage.Coverage coverage) {

    /** A result without coverage. */
    public TestResult(Verdict verdict, String explanation, long seed, int inputs, int outputs, long durationMicros) {
        this(verdict, explanation, seed, inputs, outputs, durationMicros, null);
    }

    /** TRON's statistics line: {@code seed verdict #inputs #outputs duration}. */
    public String statisticsLine() {
        return seed + " " + verdict + " " + inputs + " " + outputs + " " + durationMicros;
    }
}
