package io.dtron.model.internal;

import io.dtron.model.ChannelVariable;
import io.dtron.model.ClockVariable;
import io.dtron.model.Function;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import io.dtron.xta.Diagnostic;
import io.dtron.xta.Pos;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Set;

/** What one load builds up: diagnostics, and the variables, clocks, channels and functions of the network. */
final class Compilation {
    final Diagnostics diagnostics = new Diagnostics();
    final List<Diagnostic> startErrors = new ArrayList<>();
    final List<Variable> variables = new ArrayList<>();
    final List<ClockVariable> clocks = new ArrayList<>();
    final List<ChannelVariable> channels = new ArrayList<>();
    private final List<FunctionInfo> functionInfos = new ArrayList<>();
    private final List<Function> functions = new ArrayList<>();
    private int stateSize;
    private int clockCount;
    private int channelCount;
    private int scalarIds;
    /** While a template is checked without being instantiated, nothing it declares joins the network. */
    boolean detached;
    /** The templates declared {@code dynamic}: spawned, not listed in the system line. */
    final Set<String> dynamicTemplates = new HashSet<>();
    private final Set<String> unsupportedFeatures = new HashSet<>();
    private final Set<String> unknownNames = new HashSet<>();

    /**
     * Records that the model uses {@code feature}, which DTRON's engine cannot execute: the model loads, and
     * {@code check} says so with a warning, but every run is refused with the first such place and {@code why}.
     */
    void unsupported(Pos pos, String feature, String why) {
        unsupported(pos, feature, feature, why);
    }

    /**
     * As {@link #unsupported(Pos, String, String)}, once per {@code kind} (all built-in functions are one kind).
     * A template that no process instantiates takes no part in a run: what it uses does not stop one.
     */
    void unsupported(Pos pos, String kind, String feature, String why) {
        if (!detached && unsupportedFeatures.add(kind)) {
            String message = feature + " cannot be run by DTRON's engine: " + why;
            startErrors.add(Diagnostic.error(pos, message));
            diagnostics.warning(pos, message + "; the model can be checked, but 'dtron run' refuses it");
        }
    }

    /**
     * Whether the unknown {@code name} (a variable, function or type, as {@code what} says) is reported for the
     * first time: one undeclared name gives one error, at its first use, however often it is used.
     */
    boolean firstUnknown(String what, String name) {
        return unknownNames.add(what + " " + name);
    }

    int nextScalarId() {
        return ++scalarIds;
    }

    Variable newVariable(String name, Type type, int[] initial, boolean meta, String owner, Pos pos) {
        Variable v = new Variable(name, type, stateSize, initial, meta, owner, pos);
        if (!detached) {
            stateSize += type.slots();
            variables.add(v);
        }
        return v;
    }

    ClockVariable newClock(String name, Type type, String owner, Pos pos) {
        ClockVariable c = new ClockVariable(name, type, clockCount + 1, owner, pos);
        if (!detached) {
            clockCount += type.clocks();
            clocks.add(c);
        }
        return c;
    }

    ChannelVariable newChannel(String name, Type type, String owner, Pos pos) {
        ChannelVariable c = new ChannelVariable(name, type, channelCount, owner, pos);
        if (!detached) {
            channelCount += type.channels();
            channels.add(c);
        }
        return c;
    }

    FunctionInfo newFunction(String name, Type returnType, List<Function.Parameter> parameters) {
        FunctionInfo info = new FunctionInfo(functionInfos.size(), name, returnType, parameters);
        functionInfos.add(info);
        functions.add(null);
        return info;
    }

    void completeFunction(Function f) {
        functions.set(f.index(), f);
    }

    /** The compiled function number {@code index}, or null while its body is being compiled. */
    Function compiledFunction(int index) {
        return functions.get(index);
    }

    FunctionInfo function(int index) {
        return functionInfos.get(index);
    }

    /** The compiled functions, indexed as {@link io.dtron.model.Expression.Call#function()} counts them. */
    List<Function> functions() {
        return List.copyOf(functions);
    }

    int stateSize() {
        return stateSize;
    }

    int clockCount() {
        return clockCount;
    }

    int channelCount() {
        return channelCount;
    }
}
