package io.dtron.selenium.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;

import org.junit.jupiter.api.Test;

/** What the watch says a step's thread is doing, from its stack. */
class StepWatchTest {
    private static StackTraceElement frame(String type, String method, int line) {
        return new StackTraceElement(type, method, type.substring(type.lastIndexOf('.') + 1) + ".java", line);
    }

    @Test
    void aStepInAWebDriverCallNamesTheCallTheLineThatMadeItAndTheAdaptersLine() {
        StackTraceElement[] stack = {
            frame("jdk.internal.misc.Unsafe", "park", -2),
            frame("org.openqa.selenium.remote.HttpCommandExecutor", "execute", 100),
            frame("org.openqa.selenium.remote.RemoteWebDriver", "findElements", 200),
            frame("io.dtron.selenium.AbstractSeleniumAdapter", "findInput", 160),
            frame("com.example.web.Greet", "execute", 24),
            frame("io.dtron.selenium.AbstractSeleniumAdapter", "run", 260),
            frame("java.lang.Thread", "run", 833)};
        assertEquals("waiting in the WebDriver call RemoteWebDriver.findElements made in"
                + " AbstractSeleniumAdapter.findInput at com.example.web.Greet.execute(Greet.java:24) (innermost frame"
                + " Unsafe.park)", StepWatch.doing(stack, "com.example.web.Greet"));
    }

    @Test
    void aStepStartingItsBrowserSaysSo() {
        StackTraceElement[] stack = {
            frame("org.openqa.selenium.chrome.ChromeDriver", "<init>", 10),
            frame("io.dtron.selenium.HeadlessChrome", "create", 90),
            frame("io.dtron.selenium.internal.UserSessions$User", "browser", 70),
            frame("com.example.web.Greet", "execute", 23)};
        assertEquals("starting its browser (HeadlessChrome.create)", StepWatch.doing(stack, "com.example.web.Greet"));
    }

    @Test
    void aStepOutsideWebDriverNamesTheAdaptersLine() {
        StackTraceElement[] stack = {
            frame("java.lang.Thread", "sleep", -2),
            frame("com.example.web.Greet", "execute", 30)};
        assertEquals("running at com.example.web.Greet.execute(Greet.java:30)",
                StepWatch.doing(stack, "com.example.web.Greet"));
    }
}
