package io.dtron.engine.internal.sem;

import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/**
 * Not API. A symbolic state of a network as the engine's reports name it: each process's location as {@code
 * Process.location}, and each variable's value, array elements as {@code a[i]} and the slots of a structure as
 * {@code s#i}. The verifier's traces and the monitor's alarms say states so.
 */
public final class StateText {
    private StateText() {
    }

    /** The location of every process in {@code state}, as {@code Process.location}, in the network's order. */
    public static List<String> locations(Network network, SymState state) {
        List<String> locations = new ArrayList<>();
        for (Process p : network.processes()) {
            int l = state.location(p.index());
            if (l >= 0) {
                locations.add(p.name() + "." + p.locations().get(l).name());
            }
        }
        return locations;
    }

    /** The value of every variable in {@code state}, by name, in the network's order. */
    public static Map<String, Integer> variables(Network network, SymState state) {
        Map<String, Integer> variables = new LinkedHashMap<>();
        for (Variable v : network.variables()) {
            if (v.type() instanceof Type.Array a && a.element().slots() == 1) {
                for (int i = 0; i < a.length(); i++) {
                    variables.put(v.name() + "[" + (a.firstIndex() + i) + "]", state.var(v.offset() + i));
                }
            } else if (v.type().slots() == 1) {
                variables.put(v.name(), state.var(v.offset()));
            } else {
                for (int i = 0; i < v.type().slots(); i++) {
                    variables.put(v.name() + "#" + i, state.var(v.offset() + i));
                }
            }
        }
        return variables;
    }
}
