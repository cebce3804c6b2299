package io.dtron.models.streetlight;

import java.util.Arrays;
import java.util.Locale;
import java.util.Optional;

/** The state of a street-light controller's lamps, with the model's code and the web page's label. */
enum LightState {
    OFF(0, "Off"),
    ON(1, "On"),
    DIMMED(2, "Dimmed");

    private final int code;
    private final String label;

    LightState(int code, String label) {
        this.code = code;
        this.label = label;
    }

    /** The model's code: OFF 0, ON 1, DIMMED 2. */
    int code() {
        return code;
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
