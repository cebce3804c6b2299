package io.dtron.models.streetlight;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.Map;

/**
 * The street-light application reduced to its result codes, in process and in virtual time: answers each input
 * of the model two time units later. With {@code mixUp}, the ticked controller and the last command are kept in
 * one slot for all users, as the sample server keeps them with its session mix-up switch on.
 */
final class SimulatedStreetLights implements Adapter {
    private static final int ALL = -1;

    private final boolean mixUp;
    private final Map<Integer, Integer> selected = new HashMap<>();
    private final Map<Integer, Integer> lastCode = new HashMap<>();
    private AdapterContext context;

    SimulatedStreetLights(boolean mixUp) {
        this.mixUp = mixUp;
    }

    @Override
    public void start(AdapterContext runContext) {
        context = runContext;
    }

    @Override
    public void perform(Event input) {
        int user = input.value("user");
        int slot = mixUp ? ALL : user;
        int code = switch (input.channel()) {
            case "tick" -> {
                selected.put(slot, input.value("controller"));
                yield 0;
            }
            case "switch" -> {
                lastCode.put(slot, 1000 + 10 * selected.getOrDefault(slot, 0) + input.value("state"));
                yield 0;
            }
            case "check" -> lastCode.getOrDefault(slot, 3000);
            default -> 0;
        };
        Map<String, Integer> result = new LinkedHashMap<>();
        result.put("user", user);
        result.put("resCode", code);
        context.clock().schedule(2 * context.timeUnitMicros(), () -> context.report(new Event("result", result)));
    }
}
