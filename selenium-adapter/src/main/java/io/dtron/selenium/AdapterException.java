package io.dtron.selenium;

/**
 * An expected failure of a Selenium adapter, such as an element that is not on the page, with a message that
 * says what was looked for and where. Its message is logged without a stack trace, and the adapter's result is
 * {@link AbstractSeleniumAdapter#RESULT_FAILED}.
 */
public class AdapterException extends RuntimeException {
    private static final long serialVersionUID = 1L;

    /**
     * Creates the exception.
     *
     * @param message what failed, in the user's terms
     */
    public AdapterException(String message) {
        super(message);
    }

    /**
     * Creates the exception.
     *
     * @param message what failed, in the user's terms
     * @param cause   the underlying exception
     */
    public AdapterException(String message, Throwable cause) {
        super(message, cause);
    }
}
