package io.dtron.engine.monitor;

import io.dtron.engine.JsonString;
import io.dtron.engine.Event;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;

/**
 * A violation a {@link Monitor} found: why, when, the event (if an event revealed it), what the model allowed
 * then, and the states it could be in. Immutable; {@link #toJson()} is its one-line JSON form, {@link #busValues()}
 * its variables on the bus's reserved channel {@link #CHANNEL}.
 *
 * @param number      the violation's number in the run, from 1
 * @param reason      why it is a violation
 * @param micros      when: the event's time, or for a missed deadline the deadline
 * @param event       the event that revealed it; null when time passing did
 * @param explanation the violation in a sentence
 * @param sinceMicros the time of the last event the model allowed (or of the monitor's start)
 * @param allowed     the events the model allowed after {@code sinceMicros}, with their time windows
 * @param states      the states the model could be in at {@code sinceMicros} (at most {@link #MAX_STATES})
 * @param moreStates  how many more states there were
 */
public record Alarm(int number, Reason reason, long micros, Event event, String explanation, long sinceMicros,
                    List<Window> allowed, List<State> states, int moreStates) {
    /** The reserved bus channel on which alarms are published. */
    public static final String CHANNEL = "dtron_alarm";
    /** The most states an alarm lists. */
    public static final int MAX_STATES = 5;

    /** Why an alarm was raised. */
    public enum Reason {
        /** An event on a channel the model did not allow then (or at all). */
        UNEXPECTED_EVENT,
        /** An event on a channel the model allowed then, with values it did not allow. */
        WRONG_VALUES,
        /** Time passed a deadline: the model required an event by then and none came. */
        DEADLINE_MISSED;

        /** The name in JSON: {@code unexpected_event}, {@code wrong_values}, {@code deadline_missed}. */
        public String json() {
            return name().toLowerCase(java.util.Locale.ROOT);
        }

        /** The number on the bus: 1 unexpected event, 2 wrong values, 3 deadline missed. */
        public int code() {
            return ordinal() + 1;
        }
    }

    /**
     * An event the model allowed: on {@code channel} with {@code values}, from {@code fromMicros} to {@code
     * toMicros} (-1: without end).
     */
    public record Window(String channel, Map<String, Integer> values, long fromMicros, long toMicros) {
        public Window {
            Objects.requireNonNull(channel, "channel");
            values = Collections.unmodifiableMap(new LinkedHashMap<>(values));
        }
    }

    /**
     * A symbolic state the model could be in.
     *
     * @param locations each process's location as {@code Process.location}
     * @param variables each integer variable slot by name, in declaration order
     * @param clocks    the clocks' bounds in model time units, e.g. {@code x in [2, 5], y in [0, inf)}
     */
    public record State(List<String> locations, Map<String, Integer> variables, String clocks) {
        public State {
            locations = List.copyOf(locations);
            variables = Collections.unmodifiableMap(new LinkedHashMap<>(variables));
            Objects.requireNonNull(clocks, "clocks");
        }
    }

    public Alarm {
        Objects.requireNonNull(reason, "reason");
        Objects.requireNonNull(explanation, "explanation");
        allowed = List.copyOf(allowed);
        states = List.copyOf(states);
    }

    /**
     * The alarm's variables on the bus, where a message carries integers only: {@code number} and {@code reason}
     * ({@link Reason#code()}); the message's event time is the alarm's time, and {@link #toJson()} the whole alarm.
     */
    public Map<String, Integer> busValues() {
        Map<String, Integer> values = new LinkedHashMap<>();
        values.put("number", number);
        values.put("reason", reason.code());
        return Collections.unmodifiableMap(values);
    }

    /**
     * The alarm as one line of JSON: {@code {"kind":"alarm","number":1,"reason":"deadline_missed","t_us":...,
     * "channel":...,"values":{...},"explanation":...,"since_us":...,"allowed":[{"channel":...,"values":{...},
     * "from_us":...,"to_us":...}],"states":[{"locations":[...],"variables":{...},"clocks":...}],"more_states":0}};
     * {@code channel} and {@code values} are null for a deadline that time passing found, {@code to_us} null for a
     * window without end.
     */
    public String toJson() {
        StringBuilder sb = new StringBuilder("{\"kind\":\"alarm\",\"number\":").append(number).append(",\"reason\":\"")
                .append(reason.json()).append("\",\"t_us\":").append(micros).append(",\"channel\":")
                .append(event == null ? "null" : quote(event.channel())).append(",\"values\":")
                .append(event == null ? "null" : values(event.values())).append(",\"explanation\":")
                .append(quote(explanation)).append(",\"since_us\":").append(sinceMicros).append(",\"allowed\":[");
        for (int i = 0; i < allowed.size(); i++) {
            Window w = allowed.get(i);
            sb.append(i == 0 ? "" : ",").append("{\"channel\":").append(quote(w.channel())).append(",\"values\":")
                    .append(values(w.values())).append(",\"from_us\":").append(w.fromMicros()).append(",\"to_us\":")
                    .append(w.toMicros() < 0 ? "null" : String.valueOf(w.toMicros())).append('}');
        }
        sb.append("],\"states\":[");
        for (int i = 0; i < states.size(); i++) {
            State s = states.get(i);
            sb.append(i == 0 ? "" : ",").append("{\"locations\":[");
            for (int j = 0; j < s.locations().size(); j++) {
                sb.append(j == 0 ? "" : ",").append(quote(s.locations().get(j)));
            }
            sb.append("],\"variables\":").append(values(s.variables())).append(",\"clocks\":").append(quote(s.clocks()))
                    .append('}');
        }
        return sb.append("],\"more_states\":").append(moreStates).append('}').toString();
    }

    private static String values(Map<String, Integer> values) {
        StringBuilder sb = new StringBuilder("{");
        for (Map.Entry<String, Integer> e : values.entrySet()) {
            sb.append(sb.length() == 1 ? "" : ",").append(quote(e.getKey())).append(':').append(e.getValue());
        }
        return sb.append('}').toString();
    }

    private static String quote(String s) {
        return JsonString.quote(s);
    }
}
