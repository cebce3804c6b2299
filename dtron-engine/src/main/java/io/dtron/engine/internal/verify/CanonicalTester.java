package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.sem.Partition;
import io.dtron.model.ChannelVariable;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import io.dtron.model.Type;
import io.dtron.xta.Pos;
import java.util.ArrayList;
import java.util.List;

/**
 * The implementation of a model closed by a generated canonical tester instead of the model's own environment:
 * one process with one location and, for each input, a sending self-loop, for each output, a receiving
 * self-loop, so that every input is offered at any time and every output is taken at once. The values of the
 * variables attached to an input are offered too, each value of the variable's range, by a select, as long as
 * an input has at most {@link #MAX_VALUES} combinations; a variable whose range would pass that is sent with
 * the value it has (its initial value, as the tester never writes it), and said so in {@link #notes()}.
 *
 * @param network the closed network: the implementation's processes, in the model's order, then the tester
 * @param tester  the tester's process number in {@code network}
 * @param notes   what the tester does not offer (variables whose values it does not enumerate)
 */
record CanonicalTester(Network network, int tester, List<String> notes) {
    /** The most value combinations offered with one input. */
    static final int MAX_VALUES = 1024;
    /** The tester process's name. */
    static final String NAME = "CanonicalTester";

    CanonicalTester {
        notes = List.copyOf(notes);
    }

    /** The implementation of {@code network} (by {@code partition}) with a canonical tester of {@code ti}. */
    static CanonicalTester of(Network network, Partition partition, TestInterface ti) {
        List<Process> processes = new ArrayList<>();
        for (Process p : network.processes()) {
            if (!partition.isEnvironment(p.index())) {
                processes.add(new Process(processes.size(), p.name(), p.template(), p.locations(), p.initial(),
                        p.edges(), p.priority()));
            }
        }
        List<String> notes = new ArrayList<>();
        List<Edge> edges = new ArrayList<>();
        Pos where = network.processes().get(0).locations().get(0).pos();
        for (TestInterface.ObservableChannel c : ti.inputs()) {
            ChannelVariable cv = network.channelVariableOf(c.channel());
            where = cv.pos();
            List<Edge.Select> selects = new ArrayList<>();
            List<Expression> updates = new ArrayList<>();
            long combinations = 1;
            for (TestInterface.AttachedVariable v : c.variables()) {
                int[] range = range(v.variable().type());
                long size = (long) range[1] - range[0] + 1;
                if (combinations * size > MAX_VALUES) {
                    notes.add("input " + c.name() + " is offered with " + v.variable().name() + " as it is (initially "
                            + v.variable().initial()[0] + "): its " + size + " values are too many to offer each");
                    continue;
                }
                combinations *= size;
                int slot = selects.size();
                Type type = v.variable().type();
                selects.add(new Edge.Select(v.name(), slot, type, range[0], range[1]));
                Pos pos = v.variable().pos();
                updates.add(new Expression.Assign(pos, type, new Expression.VariableRef(pos, type, v.variable()), null,
                        new Expression.LocalRef(pos, type, slot, v.name(), false)));
            }
            edges.add(new Edge(edges.size(), 0, 0, selects, null,
                    new Edge.Sync(channel(cv, c.channel()), Edge.Direction.SEND), updates, selects.size(), cv.pos()));
        }
        for (TestInterface.ObservableChannel c : ti.outputs()) {
            ChannelVariable cv = network.channelVariableOf(c.channel());
            where = cv.pos();
            edges.add(new Edge(edges.size(), 0, 0, List.of(), null,
                    new Edge.Sync(channel(cv, c.channel()), Edge.Direction.RECEIVE), List.of(), 0, cv.pos()));
        }
        int tester = processes.size();
        processes.add(new Process(tester, NAME, NAME,
                List.of(new Location(0, "offering", Location.Kind.NORMAL, null, 0, where)), 0, edges, 0));
        Network closed = new Network(network.file(), processes, network.variables(), network.clocks(),
                network.channels(), network.functions(), network.stateSize(), network.clockCount(),
                network.channelCount(), network.channelPriority(), List.of(), network.warnings(),
                network.startErrors());
        return new CanonicalTester(closed, tester, notes);
    }

    /** The lowest and highest value of an attached variable's type (an int range or a bool). */
    private static int[] range(Type type) {
        if (type instanceof Type.Int i) {
            return new int[] {i.lower(), i.upper()};
        }
        return new int[] {0, 1};
    }

    /** The expression of channel number {@code index}, an element of {@code cv}. */
    private static Expression channel(ChannelVariable cv, int index) {
        Expression e = new Expression.ChannelRef(cv.pos(), cv.type(), cv);
        Type type = cv.type();
        int offset = index - cv.index();
        while (type instanceof Type.Array a) {
            int size = a.element().channels();
            e = new Expression.Index(cv.pos(), a.element(), e,
                    new Expression.Constant(cv.pos(), Type.Int.DEFAULT, a.firstIndex() + offset / size));
            offset %= size;
            type = a.element();
        }
        return e;
    }
}
