package io.dtron.selenium.internal;

import io.dtron.selenium.AdapterException;

/**
 * Not API. A failure of the adapters' own machinery, not of the system under test: a user's browser that cannot
 * be started or cannot open its start page. The step it happens in cannot be done, and no result may blame the
 * system under test for it.
 */
public final class BrowserFailure extends AdapterException {
    private static final long serialVersionUID = 1L;

    /**
     * Creates the exception.
     *
     * @param message what failed
     * @param cause   the underlying exception
     */
    public BrowserFailure(String message, Throwable cause) {
        super(message, cause);
    }
}
