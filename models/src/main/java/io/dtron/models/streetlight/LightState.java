package io.dtron.models.streetlight;

import java.util.Arrays;
import java.util.Locale;
import java.util.Optional;

/** The state of a street-light controller's lamps, with the web page's label. */
enum LightState {
    OFF("Off"),
    ON("On"),
    DIMMED("Dimmed");

    private final String label;

    LightState(String label) {
        this.label = label;
    }

    /** The label on the web pages. */
    String label() {
        return label;
    }

    /** The state named {@code name} (any case), if there is one. */
    static Optional<LightState> parse(String name) {
        return Arrays.stream(values()).filter(s -> s.name().equals(name.toUpperCase(Locale.ROOT))).findFirst();
    }
}
