package io.dtron.selenium;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;

/**
 * The sample adapters, one browser started before the run, on Chromium whose first page load takes
 * {@value #FIRST_LOAD_MILLIS} ms (as a browser's first page load can on a busy machine) and later ones as usual:
 * for {@code dtron run --adapter io.dtron.selenium.FirstLoadAdapters:VARIANT}. Variant {@code cold} leaves the
 * browser on its blank page, so the first load is in user 0's first step; {@code warm} opens the site's form as
 * the start page before the run. The site's address comes from the system property {@code BASE_URL}.
 */
public final class FirstLoadAdapters implements DtronAdapter {
    static final long FIRST_LOAD_MILLIS = 6_000;

    private final SeleniumAdapters adapters;

    /** The adapters of a variant, {@code cold} or {@code warm}. */
    public FirstLoadAdapters(String variant) {
        SeleniumAdapters.Builder builder = SeleniumAdapters.builder().scan("io.dtron.selenium.sample")
                .driverFactory(new StallingChrome(FIRST_LOAD_MILLIS, true)).browsers(1);
        switch (variant) {
            case "cold" -> { }
            case "warm" -> builder.startPage(System.getProperty("BASE_URL") + "/form");
            default -> throw new IllegalArgumentException("variant cold or warm: " + variant);
        }
        adapters = builder.build();
    }

    @Override
    public void start(Dtron dtron) {
        adapters.start(dtron);
    }

    @Override
    public void close() {
        adapters.close();
    }
}
