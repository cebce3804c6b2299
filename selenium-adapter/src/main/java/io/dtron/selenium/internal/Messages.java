package io.dtron.selenium.internal;

/** Not API. Shortens the messages of Selenium and Guice for the log and for verdicts. */
public final class Messages {
    private Messages() {
    }

    /** Returns the first line of a message (Selenium's go on with build and system information); "" for null. */
    public static String firstLine(String message) {
        if (message == null) {
            return "";
        }
        int end = message.indexOf('\n');
        return end < 0 ? message : message.substring(0, end);
    }
}
