package io.dtron.selenium;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;

/**
 * The sample adapters on browsers whose page loads stall for {@value #STALL_MILLIS} ms in the WebDriver call, with
 * a step timeout of {@value #STEP_TIMEOUT_MILLIS} ms: for {@code dtron run --adapter}. The site's address comes
 * from the system property {@code BASE_URL}.
 */
public final class StallingAdapters implements DtronAdapter {
    static final long STALL_MILLIS = 20_000;
    static final long STEP_TIMEOUT_MILLIS = 2_000;

    private final SeleniumAdapters adapters = SeleniumAdapters.builder().scan("io.dtron.selenium.sample")
            .driverFactory(new StallingChrome(STALL_MILLIS)).browsers(1)
            .property(SeleniumAdapters.SLOW_STEP_PROPERTY, "500")
            .property(SeleniumAdapters.STEP_TIMEOUT_PROPERTY, Long.toString(STEP_TIMEOUT_MILLIS)).build();

    @Override
    public void start(Dtron dtron) {
        adapters.start(dtron);
    }

    @Override
    public void close() {
        adapters.close();
    }
}
