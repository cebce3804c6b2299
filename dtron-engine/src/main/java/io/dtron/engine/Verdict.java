package io.dtron.engine;

/** The outcome of a test run, as Uppaal TRON gives it, with TRON's exit codes. */
public enum Verdict {
    /** The timeout was reached and every observation conformed to the model. */
    PASSED(0),
    /** The system under test did something the model does not allow, or failed to do what it requires. */
    FAILED(2),
    /** The test could not go on: the environment model could not accept an output, or an input came too late. */
    INCONCLUSIVE(3);

    private final int exitCode;

    Verdict(int exitCode) {
        this.exitCode = exitCode;
    }

    /** The process exit code for this verdict: 0, 2 or 3. */
    public int exitCode() {
        return exitCode;
    }
}
