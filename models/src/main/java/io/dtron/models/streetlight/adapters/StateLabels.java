package io.dtron.models.streetlight.adapters;

import io.dtron.selenium.AdapterException;
import jakarta.inject.Inject;
import jakarta.inject.Named;
import java.util.List;

/** The labels of the light states on the pages, by the model's numbers OFF 0, ON 1, DIMMED 2. */
public final class StateLabels {
    private final List<String> labels;

    /** The labels from the adapters' properties. */
    @Inject
    public StateLabels(@Named("STATE_0") String off, @Named("STATE_1") String on, @Named("STATE_2") String dimmed) {
        this.labels = List.of(off, on, dimmed);
    }

    /**
     * Returns the label of a state.
     *
     * @throws AdapterException if the model's number is no state
     */
    public String label(int state) {
        if (state < 0 || state >= labels.size()) {
            throw new AdapterException("no light state " + state + ": the model numbers OFF 0, ON 1, DIMMED 2");
        }
        return labels.get(state);
    }

    /**
     * Returns the model's number of a label.
     *
     * @throws AdapterException if the label is none of the states'
     */
    public int state(String label) {
        int state = labels.indexOf(label);
        if (state < 0) {
            throw new AdapterException("the page shows state '" + label + "', none of " + labels);
        }
        return state;
    }
}
