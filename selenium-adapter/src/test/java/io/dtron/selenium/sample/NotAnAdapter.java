package io.dtron.selenium.sample;

/** A class that is no adapter: scanning skips it. */
public final class NotAnAdapter {
    private NotAnAdapter() {
    }
}
