package io.dtron.models.streetlight;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.selenium.SeleniumAdapters;
import java.io.IOException;
import java.io.UncheckedIOException;

/**
 * The street-light sample as one bus adapter: starts the web application ({@link StreetLightServer}, two
 * controllers per operator) and the Selenium adapters of {@value #ADAPTERS_PACKAGE}, one headless Chromium per
 * operator. So {@code dtron run streetlight-4.xml --timeunit 100000 --adapter
 * io.dtron.models.streetlight.StreetLightWebTest:4} tests the application with four operators at once, and
 * {@code ...StreetLightWebTest:4,mixup} the application with its session mix-up.
 */
public final class StreetLightWebTest implements DtronAdapter {
    /** The package of the street-light adapters. */
    public static final String ADAPTERS_PACKAGE = "io.dtron.models.streetlight.adapters";

    private final int users;
    private final boolean sessionMixUp;
    private StreetLightServer server;
    private SeleniumAdapters adapters;

    /** One operator, the correct application. */
    public StreetLightWebTest() {
        this("1");
    }

    /**
     * The variant {@code USERS} or {@code USERS,mixup}: the number of operators (as the model's {@code USERS}),
     * and whether the application mixes up their sessions.
     *
     * @throws IllegalArgumentException if the variant is neither
     */
    public StreetLightWebTest(String variant) {
        String[] parts = variant.split(",", -1);
        try {
            users = Integer.parseInt(parts[0].trim());
        } catch (NumberFormatException e) {
            throw usage(variant);
        }
        if (parts.length > 2 || parts.length == 2 && !parts[1].trim().equals("mixup") || users < 1
                || users > StreetLightModel.MAX_USERS) {
            throw usage(variant);
        }
        sessionMixUp = parts.length == 2;
    }

    private static IllegalArgumentException usage(String variant) {
        return new IllegalArgumentException("variant '" + variant + "': give the number of operators (1 to "
                + StreetLightModel.MAX_USERS + "), optionally followed by ',mixup', e.g. 4,mixup");
    }

    /** Returns the number of operators. */
    public int users() {
        return users;
    }

    /** Returns whether the application mixes up the operators' sessions. */
    public boolean sessionMixUp() {
        return sessionMixUp;
    }

    /**
     * Starts the application, the operators' browsers and the adapters.
     *
     * @throws UncheckedIOException if the application cannot start
     */
    @Override
    public void start(Dtron dtron) {
        try {
            server = new StreetLightServer(2 * users, sessionMixUp).start();
            adapters = SeleniumAdapters.builder().scan(ADAPTERS_PACKAGE).property("BASE_URL", server.url())
                    .browsers(users).startPage(server.url() + "/login").build();
            adapters.start(dtron);
        } catch (IOException e) {
            close();
            throw new UncheckedIOException(e.getMessage(), e);
        } catch (RuntimeException e) {
            close();
            throw e;
        }
    }

    /** Stops the adapters, quits the browsers and stops the application. */
    @Override
    public void close() {
        try {
            if (adapters != null) {
                adapters.close();
            }
        } finally {
            if (server != null) {
                server.close();
            }
        }
    }
}
