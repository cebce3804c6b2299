package io.dtron.api.internal;

import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.InvalidMessageException;
import io.dtron.api.InvalidMessageException.Reason;
import java.util.ArrayList;
import java.util.Collection;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.regex.Pattern;

/** Not API. The immutable {@link IDtronChannel}. */
public final class DtronChannel implements IDtronChannel {
    private static final Pattern IDENTIFIER = Pattern.compile("[A-Za-z_][A-Za-z0-9_]*");

    private final String name;
    private final List<String> variableNames;
    private final Set<String> variableSet;

    /**
     * Creates a template.
     *
     * @throws IllegalArgumentException if a name is no identifier or a variable name repeats
     */
    public DtronChannel(String name, List<String> variableNames) {
        this.name = requireIdentifier(name, "channel name");
        this.variableNames = List.copyOf(variableNames);
        this.variableSet = new HashSet<>();
        for (String variable : this.variableNames) {
            if (!variableSet.add(requireIdentifier(variable, "variable name"))) {
                throw new IllegalArgumentException("variable " + variable + " appears twice in channel " + name);
            }
        }
    }

    /** Returns the template itself if it is a {@code DtronChannel}, else an equal-named copy. */
    public static DtronChannel copyOf(IDtronChannel channel) {
        return channel instanceof DtronChannel own
                ? own
                : new DtronChannel(channel.getChannelName(), channel.getVariableNames());
    }

    /** Implements {@link IDtronChannel#fromModel}. */
    public static DtronChannel fromModel(String modelChannel, Collection<String> attachedVariables) {
        requireIdentifier(modelChannel, "channel name");
        String busName = modelChannel.startsWith("i_") || modelChannel.startsWith("o_")
                ? modelChannel.substring(2)
                : modelChannel;
        String variablePrefix = modelChannel + "_";
        List<String> variables = new ArrayList<>();
        for (String variable : attachedVariables) {
            variables.add(variable.startsWith(variablePrefix) && variable.length() > variablePrefix.length()
                    ? variable.substring(variablePrefix.length())
                    : variable);
        }
        return new DtronChannel(busName, variables);
    }

    private static String requireIdentifier(String text, String what) {
        Objects.requireNonNull(text, what);
        if (!IDENTIFIER.matcher(text).matches()) {
            throw new IllegalArgumentException(what + " is no identifier: '" + text + "'");
        }
        return text;
    }

    @Override
    public String getChannelName() {
        return name;
    }

    @Override
    public List<String> getVariableNames() {
        return variableNames;
    }

    /** Returns whether another template has the same name and the same variables, in any order. */
    public boolean isCompatible(IDtronChannel other) {
        return name.equals(other.getChannelName()) && variableSet.equals(Set.copyOf(other.getVariableNames()));
    }

    /**
     * Checks that a set of names is exactly this template's variables.
     *
     * @throws InvalidMessageException naming the unknown, else the missing variables
     */
    public void checkVariables(Collection<String> names) {
        List<String> unknown = names.stream().filter(n -> !variableSet.contains(n)).sorted().toList();
        List<String> missing = variableNames.stream().filter(n -> !names.contains(n)).toList();
        if (!unknown.isEmpty()) {
            throw new InvalidMessageException(Reason.UNKNOWN_VARIABLES, "channel " + name + " has no variable "
                    + String.join(", ", unknown) + (missing.isEmpty() ? "" : "; missing " + String.join(", ", missing))
                    + " (variables: " + variableNames + ")");
        }
        if (!missing.isEmpty()) {
            throw new InvalidMessageException(Reason.MISSING_VARIABLES, "channel " + name + " needs variable "
                    + String.join(", ", missing) + " (variables: " + variableNames + ")");
        }
    }

    @Override
    public IDtronChannelValued constructValued(Map<String, Integer> values) {
        Objects.requireNonNull(values, "values");
        checkVariables(values.keySet());
        Map<String, Integer> ordered = new LinkedHashMap<>();
        for (String variable : variableNames) {
            ordered.put(variable, Objects.requireNonNull(values.get(variable), () -> "value of " + variable));
        }
        return new DtronChannelValued(this, ordered, Stamp.NONE, 0);
    }

    @Override
    public IDtronChannelValued constructValued(byte[] message) {
        Objects.requireNonNull(message, "message");
        return SyncCodec.decode(this, SyncCodec.parse(message), "", 0);
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof DtronChannel other && name.equals(other.name) && variableNames.equals(other.variableNames);
    }

    @Override
    public int hashCode() {
        return Objects.hash(name, variableNames);
    }

    @Override
    public String toString() {
        return name + variableNames;
    }
}
