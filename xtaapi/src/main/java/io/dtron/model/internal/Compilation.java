package io.dtron.model.internal;

import io.dtron.model.ChannelVariable;
import io.dtron.model.ClockVariable;
import io.dtron.model.Function;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import io.dtron.xta.Diagnostic;
import io.dtron.xta.Pos;
import java.util.ArrayList;
import java.util.List;

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
