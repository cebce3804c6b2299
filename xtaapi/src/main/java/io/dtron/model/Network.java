package io.dtron.model;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.ast.Query;
import java.util.List;
import java.util.Optional;

/**
 * A loaded, type-checked model: its processes with locations and edges, its variables laid out in one
 * integer state vector, its clocks and channels. Immutable; every other module reads models through this.
 *
 * @param file             the file (or resource, or store entry) it was loaded from
 * @param processes        the processes, in the order of the system line
 * @param variables        the integer variables, global and local, in state-vector order
 * @param clocks           the clocks, global and local
 * @param channels         the channels, global and local
 * @param functions        the user functions, global and per process
 * @param stateSize        the number of slots of the integer state vector
 * @param clockCount       the number of clocks, without the reference clock
 * @param channelCount     the number of channels
 * @param channelPriority  the priority of each channel (0 is the default level)
 * @param queries          the model's queries as written, each with its kind, text and place; one that does not
 *                         parse has kind {@code INVALID} and its errors, which are not errors of the model
 * @param warnings         warnings found while loading, sorted by file, line and column
 * @param startErrors      errors that do not stop loading but stop any run: the initial state cannot be
 *                         computed (e.g. an argument out of an array's bounds in one expanded process), or the
 *                         model uses what DTRON's engine cannot execute (statistical model checking: doubles,
 *                         branchpoints, dynamic templates, external and random functions), one per kind of
 *                         construct, at its first place
 */
public record Network(String file, List<Process> processes, List<Variable> variables, List<ClockVariable> clocks,
                      List<ChannelVariable> channels, List<Function> functions, int stateSize, int clockCount,
                      int channelCount, List<Integer> channelPriority, List<Query> queries,
                      List<Diagnostic> warnings, List<Diagnostic> startErrors) {
    public Network {
        processes = List.copyOf(processes);
        variables = List.copyOf(variables);
        clocks = List.copyOf(clocks);
        channels = List.copyOf(channels);
        functions = List.copyOf(functions);
        channelPriority = List.copyOf(channelPriority);
        queries = List.copyOf(queries);
        warnings = List.copyOf(warnings);
        startErrors = List.copyOf(startErrors);
    }

    /** The process called {@code name}. */
    public Optional<Process> process(String name) {
        return processes.stream().filter(p -> p.name().equals(name)).findFirst();
    }

    /** The global or local variable with this qualified name. */
    public Optional<Variable> variable(String name) {
        return variables.stream().filter(v -> v.name().equals(name)).findFirst();
    }

    /** The global or local clock (or clock array) with this qualified name. */
    public Optional<ClockVariable> clock(String name) {
        return clocks.stream().filter(v -> v.name().equals(name)).findFirst();
    }

    /** The global or local channel (or channel array) with this qualified name. */
    public Optional<ChannelVariable> channel(String name) {
        return channels.stream().filter(v -> v.name().equals(name)).findFirst();
    }

    /** The channel variable that channel number {@code index} belongs to. */
    public ChannelVariable channelVariableOf(int index) {
        for (ChannelVariable c : channels) {
            if (index >= c.index() && index < c.index() + c.type().channels()) {
                return c;
            }
        }
        throw new IllegalArgumentException("no channel " + index);
    }

    /** The name of channel number {@code index}, e.g. {@code appr[2]}. */
    public String channelName(int index) {
        return channelVariableOf(index).elementName(index);
    }

    /** The initial integer state vector. */
    public int[] initialState() {
        int[] state = new int[stateSize];
        for (Variable v : variables) {
            System.arraycopy(v.initial(), 0, state, v.offset(), v.size());
        }
        return state;
    }

    /** The names of the templates that the processes instantiate, without repetition. */
    public List<String> templates() {
        return processes.stream().map(Process::template).distinct().toList();
    }
}
