package io.dtron.tron.internal;

import io.dtron.engine.TestOptions;
import io.dtron.model.ChannelVariable;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.model.Variable;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.Collections;
import java.util.List;
import java.util.Map;
import java.util.Optional;

/**
 * The tester's side of the configuration phase: resolves what the adapter registers against the model and
 * answers with channel ids or error codes, keeps the explanation of each error for command 127, and builds the
 * {@link TestInterface}. Channel names are the model's global channels, or elements of global channel arrays
 * written {@code name[index]}; variables are global int or bool variables.
 */
public final class InterfaceRegistry {
    /** An unknown command; the tester closes the connection after answering it. */
    public static final int UNKNOWN_COMMAND = -1;
    /** The channel is not a global channel of the model. */
    public static final int NO_SUCH_CHANNEL = -2;
    /** The channel was already registered in the other direction. */
    public static final int CHANNEL_TWICE = -3;
    /** The name is a whole channel array. */
    public static final int CHANNEL_ARRAY = -4;
    /** The channel id was never given out. */
    public static final int NO_SUCH_CHANNEL_ID = -5;
    /** The channel id is of the other direction. */
    public static final int WRONG_DIRECTION = -6;
    /** The variable is not a global variable of the model. */
    public static final int NO_SUCH_VARIABLE = -7;
    /** The variable is not a single int or bool. */
    public static final int NOT_AN_INTEGER = -8;
    /** The variable is already attached to that channel. */
    public static final int VARIABLE_TWICE = -9;
    /** The time unit is not positive. */
    public static final int BAD_TIME_UNIT = -10;
    /** The timeout is not positive. */
    public static final int BAD_TIMEOUT = -11;
    /** The shared virtual clock was asked for in a real-time run. */
    public static final int NO_VIRTUAL_CLOCK = -12;
    /** The timeout times the time unit is longer than the engine can time ({@link TestOptions#MAX_DURATION_MICROS}). */
    public static final int RUN_TOO_LONG = -13;

    private static final Map<Integer, String> GENERIC = Map.ofEntries(
            Map.entry(UNKNOWN_COMMAND, "unknown command; the tester closes the connection"),
            Map.entry(NO_SUCH_CHANNEL, "no such global channel in the model"),
            Map.entry(CHANNEL_TWICE, "the channel is already registered in the other direction"),
            Map.entry(CHANNEL_ARRAY, "a channel array: register its elements, e.g. name[0]"),
            Map.entry(NO_SUCH_CHANNEL_ID, "no channel was registered with that id"),
            Map.entry(WRONG_DIRECTION, "the channel id belongs to a channel of the other direction"),
            Map.entry(NO_SUCH_VARIABLE, "no such global variable in the model"),
            Map.entry(NOT_AN_INTEGER, "only global int and bool variables travel with events"),
            Map.entry(VARIABLE_TWICE, "the variable is already attached to that channel"),
            Map.entry(BAD_TIME_UNIT, "the time unit must be a positive number of microseconds"),
            Map.entry(BAD_TIMEOUT, "the timeout must be a positive number of model time units"),
            Map.entry(NO_VIRTUAL_CLOCK, "the shared virtual clock needs a run in virtual time"),
            Map.entry(RUN_TOO_LONG, "the timeout times the time unit is longer than DTRON can time: at most "
                    + TestOptions.MAX_DURATION_MICROS + " us"));

    private final Network network;
    private final Map<String, Integer> channelIndexByName = new LinkedHashMap<>();
    private final Map<Integer, Registered> byId = new LinkedHashMap<>();
    private final Map<Integer, String> explanations = new HashMap<>();
    private final List<String> refusals = new ArrayList<>();
    private Long timeUnitMicros;
    private Long timeout;

    /** A registry for {@code network}'s global channels and variables. */
    public InterfaceRegistry(Network network) {
        this.network = network;
        for (ChannelVariable c : network.channels()) {
            if (c.owner() == null) {
                for (int k = 0; k < c.type().channels(); k++) {
                    channelIndexByName.put(c.elementName(c.index() + k), c.index() + k);
                }
            }
        }
    }

    /** A channel the adapter registered. */
    public static final class Registered {
        private final int id;
        private final String name;
        private final int channel;
        private final boolean input;
        private final List<TestInterface.AttachedVariable> variables = new ArrayList<>();

        Registered(int id, String name, int channel, boolean input) {
            this.id = id;
            this.name = name;
            this.channel = channel;
            this.input = input;
        }

        /** Its id on the wire. */
        public int id() {
            return id;
        }

        /** Its name (the model's, as registered). */
        public String name() {
            return name;
        }

        /** Whether it is an input. */
        public boolean input() {
            return input;
        }

        /** The attached variables in the order they were attached: the order of their values on the wire. */
        public List<TestInterface.AttachedVariable> variables() {
            return Collections.unmodifiableList(variables);
        }

        TestInterface.ObservableChannel toChannel() {
            return new TestInterface.ObservableChannel(name, channel, name, variables);
        }
    }

    /**
     * Registers an input or output; returns its id (positive) or an error code. A channel registered again in the
     * same direction gets the same id again, as TRON gives it; in the other direction it is refused.
     */
    public int registerChannel(String rawName, boolean input) {
        String name = rawName.replaceAll("\\s+", "");
        String kind = input ? "input" : "output";
        Integer index = channelIndexByName.get(name);
        if (index == null) {
            Optional<ChannelVariable> array = network.channel(name).filter(c -> c.owner() == null);
            if (array.isPresent()) {
                return refuse(CHANNEL_ARRAY, kind + " '" + name + "' is a channel array: register its elements, e.g. '"
                        + array.get().elementName(array.get().index()) + "'");
            }
            return refuse(NO_SUCH_CHANNEL, kind + " '" + Wire.printable(rawName) + "' is not a global channel of "
                    + modelName() + "; its global channels: " + channelList());
        }
        for (Registered r : byId.values()) {
            if (r.name.equals(name)) {
                if (r.input == input) {
                    return r.id; // as TRON does: the same channel again gets its id again
                }
                return refuse(CHANNEL_TWICE, kind + " '" + name + "' is already registered as "
                        + (r.input ? "input" : "output") + " " + r.id);
            }
        }
        int id = byId.size() + 1;
        byId.put(id, new Registered(id, name, index, input));
        return id;
    }

    /** Attaches a variable to a registered channel; returns 0 or an error code. */
    public int attachVariable(int channelId, String rawName, boolean input) {
        String kind = input ? "input" : "output";
        Registered channel = byId.get(channelId);
        if (channel == null) {
            return refuse(NO_SUCH_CHANNEL_ID, "cannot attach '" + Wire.printable(rawName) + "' to " + kind
                    + " channel id " + channelId + ": no channel has that id (" + registeredList() + ")");
        }
        if (channel.input != input) {
            return refuse(WRONG_DIRECTION, "cannot attach '" + Wire.printable(rawName) + "' with command "
                    + (input ? 3 : 4) + ": channel id " + channelId + " ('" + channel.name + "') is an "
                    + (channel.input ? "input" : "output"));
        }
        String name = rawName.strip();
        Optional<Variable> variable = network.variable(name).filter(v -> v.owner() == null);
        if (variable.isEmpty()) {
            String what = network.clock(name).filter(c -> c.owner() == null).isPresent() ? "is a clock, not an int"
                    : "is not a global variable of " + modelName();
            return refuse(NO_SUCH_VARIABLE, "cannot attach '" + Wire.printable(rawName) + "' to " + kind + " '"
                    + channel.name + "': it " + what);
        }
        if (variable.get().size() != 1 || !variable.get().type().isIntegral()) {
            return refuse(NOT_AN_INTEGER, "cannot attach '" + name + "' to " + kind + " '" + channel.name
                    + "': it is " + variable.get().type() + "; only global int and bool variables travel with events");
        }
        for (TestInterface.AttachedVariable v : channel.variables) {
            if (v.name().equals(name)) {
                return refuse(VARIABLE_TWICE, "'" + name + "' is already attached to " + kind + " '" + channel.name
                        + "'");
            }
        }
        channel.variables.add(new TestInterface.AttachedVariable(name, variable.get()));
        return 0;
    }

    /** Sets the time unit from seconds and microseconds; returns 0 or an error code. */
    public int setTimeUnit(int seconds, int micros) {
        long total = seconds * 1_000_000L + micros;
        if (seconds < 0 || micros < 0 || total <= 0) {
            return refuse(BAD_TIME_UNIT, "time unit " + seconds + " s " + micros + " us: it must be a positive number"
                    + " of microseconds");
        }
        if (timeout != null && !TestOptions.fits(timeout, total)) {
            return refuse(RUN_TOO_LONG, "time unit " + seconds + " s " + micros + " us: "
                    + TestOptions.tooLong("with it, the timeout", timeout, total));
        }
        timeUnitMicros = total;
        return 0;
    }

    /** Sets the timeout in model time units; returns 0 or an error code. */
    public int setTimeout(int units) {
        if (units <= 0) {
            return refuse(BAD_TIMEOUT, "timeout " + units + ": it must be a positive number of model time units");
        }
        if (timeUnitMicros != null && !TestOptions.fits(units, timeUnitMicros)) {
            return refuse(RUN_TOO_LONG, "timeout " + units + ": " + TestOptions.tooLong("the timeout", units,
                    timeUnitMicros));
        }
        timeout = (long) units;
        return 0;
    }

    /** Refuses the shared virtual clock (a real-time run). */
    public int refuseVirtualClock() {
        return refuse(NO_VIRTUAL_CLOCK, "the shared virtual clock was asked for, but the tester runs in real time;"
                + " start the adapter in real time, or the tester in virtual time");
    }

    /** Records an unknown command. */
    public int unknownCommand(String message) {
        return refuse(UNKNOWN_COMMAND, message);
    }

    /** The explanation of an error code: the last refusal with that code, or its generic text. */
    public String explain(int code) {
        String specific = explanations.get(code);
        if (specific != null) {
            return specific;
        }
        return GENERIC.getOrDefault(code, "no such error code: " + code);
    }

    /** Every refusal so far, in order. */
    public List<String> refusals() {
        return List.copyOf(refusals);
    }

    /** The registered channel with this id, if any. */
    public Optional<Registered> channel(int id) {
        return Optional.ofNullable(byId.get(id));
    }

    /** The registered channels in id order. */
    public List<Registered> channels() {
        return List.copyOf(byId.values());
    }

    /** A list of the registered channels, for messages. */
    public String registeredList() {
        if (byId.isEmpty()) {
            return "no channel is registered";
        }
        StringBuilder sb = new StringBuilder("registered: ");
        String sep = "";
        for (Registered r : byId.values()) {
            sb.append(sep).append(r.id).append(' ').append(r.input ? "input " : "output ").append(r.name);
            sep = ", ";
        }
        return sb.toString();
    }

    /** The interface built from the registrations. */
    public TestInterface build() {
        List<TestInterface.ObservableChannel> inputs = new ArrayList<>();
        List<TestInterface.ObservableChannel> outputs = new ArrayList<>();
        for (Registered r : byId.values()) {
            (r.input ? inputs : outputs).add(r.toChannel());
        }
        return new TestInterface(inputs, outputs, timeUnitMicros, timeout);
    }

    private int refuse(int code, String message) {
        explanations.put(code, message);
        refusals.add(message);
        return code;
    }

    private String modelName() {
        return network.file();
    }

    private String channelList() {
        List<String> names = new ArrayList<>(channelIndexByName.keySet());
        if (names.size() > 12) {
            return String.join(", ", names.subList(0, 12)) + ", ... (" + names.size() + " in all)";
        }
        return names.isEmpty() ? "none" : String.join(", ", names);
    }
}
