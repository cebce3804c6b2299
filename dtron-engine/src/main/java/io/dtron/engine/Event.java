package io.dtron.engine;

import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Objects;

/**
 * An event on an observable channel: an input the tester applies, or an output the system under test
 * produces, with the values of the variables attached to the channel (named without the channel prefix, in
 * declaration order). Immutable.
 *
 * @param channel the channel's interface name ({@code move} for the model's {@code i_move})
 * @param values  the attached variables' values
 */
public record Event(String channel, Map<String, Integer> values) {
    public Event {
        Objects.requireNonNull(channel, "channel");
        values = Collections.unmodifiableMap(new LinkedHashMap<>(values));
    }

    /** An event without values. */
    public static Event of(String channel) {
        return new Event(channel, Map.of());
    }

    /** An event with one value. */
    public static Event of(String channel, String variable, int value) {
        return new Event(channel, Map.of(variable, value));
    }

    /** The value of {@code variable}; throws if the event does not carry it. */
    public int value(String variable) {
        Integer v = values.get(variable);
        if (v == null) {
            throw new IllegalArgumentException("event " + this + " has no variable '" + variable + "'");
        }
        return v;
    }

    @Override
    public String toString() {
        StringBuilder sb = new StringBuilder(channel).append('(');
        boolean first = true;
        for (Map.Entry<String, Integer> e : values.entrySet()) {
            sb.append(first ? "" : ", ").append(e.getKey()).append('=').append(e.getValue());
            first = false;
        }
        return sb.append(')').toString();
    }
}
