package io.dtron.models.ticker;

import java.util.Arrays;
import java.util.List;

/** The variants of the ticker systems: the correct one and a faulty one, with their periods in time units. */
enum TickerVariant {
    CORRECT("correct", 10),
    SLOW("slow", 13);

    /** The names of the variants, the correct ticker first. */
    static final List<String> LABELS = Arrays.stream(values()).map(v -> v.label).toList();

    final String label;
    final int period;

    TickerVariant(String label, int period) {
        this.label = label;
        this.period = period;
    }

    /**
     * The variant called {@code label}.
     *
     * @throws IllegalArgumentException naming {@code owner} and the known variants, if there is none
     */
    static TickerVariant named(String label, Class<?> owner) {
        return Arrays.stream(values()).filter(v -> v.label.equals(label)).findFirst()
                .orElseThrow(() -> new IllegalArgumentException("unknown variant '" + label + "' of "
                        + owner.getName() + "; known variants: " + String.join(", ", LABELS)));
    }
}
