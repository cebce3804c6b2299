package io.dtron.junit.internal;

/**
 * A run ended INCONCLUSIVE: not an {@link AssertionError}, so that JUnit and Surefire report an error (the test
 * said nothing about the system), not a failure of the system.
 */
public final class Inconclusive extends RuntimeException {
    private static final long serialVersionUID = 1L;

    Inconclusive(String message) {
        super(message, null, false, false);
    }
}
