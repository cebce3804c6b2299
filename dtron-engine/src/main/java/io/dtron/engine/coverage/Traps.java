package io.dtron.engine.coverage;

import io.dtron.engine.internal.coverage.Recorder;
import io.dtron.model.Network;
import java.util.Collection;
import java.util.List;

/**
 * The traps of a model: its bool variables and arrays whose name (without the process) starts with {@code trap}
 * or {@code t_}, and those named (qualified, {@code Lamp.seen}, or not) with {@code --traps}; each element of an
 * array is one trap. A trap is set when the variable is true. The thesis's reactive planning tester marks the
 * edges a test must cover with an update {@code t[i] = true}: name such an array with {@code --traps t}.
 */
public final class Traps {
    private Traps() {
    }

    /**
     * The traps of {@code network} with the variables {@code named} too, in state-vector order ({@code t[2]}).
     *
     * @throws IllegalArgumentException naming those of {@code named} that are no bool variable or array
     */
    public static List<String> of(Network network, Collection<String> named) {
        List<String> unknown = Recorder.notTraps(network, named);
        if (!unknown.isEmpty()) {
            throw new IllegalArgumentException("no bool variable or array called " + String.join(", ", unknown)
                    + " to count as a trap");
        }
        return Recorder.trapNames(network, named);
    }
}
