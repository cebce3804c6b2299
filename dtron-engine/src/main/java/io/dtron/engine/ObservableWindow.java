package io.dtron.engine;

import io.dtron.model.ClockVariable;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import io.dtron.xta.Pos;
import java.util.HashMap;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;

/**
 * The time window of an observable action as one edge of the model writes it: the edge's guard bounds a clock
 * from below and the guard or its source location's invariant from above, so the action can happen only while
 * the clock is between the two. On the bus, the delays of messages and the clocks' errors eat into the narrowest
 * such window first: a tester compares them before a run (see {@link #narrowest}). Immutable.
 *
 * @param channel the observable channel's name in the model ({@code o_tick})
 * @param process the process whose edge it is
 * @param clock   the clock the bounds constrain ({@code x}, {@code c[2]})
 * @param lower   the lower bound, in model time units
 * @param upper   the upper bound, in model time units, not below {@code lower}
 * @param pos     where the edge was written
 */
public record ObservableWindow(String channel, String process, String clock, int lower, int upper, Pos pos) {

    /**
     * Checks the values.
     *
     * @throws IllegalArgumentException if the upper bound is below the lower one
     */
    public ObservableWindow {
        Objects.requireNonNull(channel, "channel");
        Objects.requireNonNull(process, "process");
        Objects.requireNonNull(clock, "clock");
        Objects.requireNonNull(pos, "pos");
        if (upper < lower) {
            throw new IllegalArgumentException("empty window " + lower + ".." + upper);
        }
    }

    /** Returns the window's width in model time units. */
    public long width() {
        return (long) upper - lower;
    }

    /** Describes the window: {@code o_tick in Ticker (10 <= x <= 12, ticker.xml:14:9)}. */
    @Override
    public String toString() {
        return channel + " in " + process + " (" + lower + " <= " + clock + " <= " + upper + ", " + pos.fragment()
                .file() + ":" + pos.line() + ":" + pos.column() + ")";
    }

    /**
     * Returns the narrowest window among the edges on the interface's channels (inputs and outputs) whose guard
     * bounds a clock from below by a constant and whose guard or source invariant bounds it from above; empty if no
     * edge has both bounds. Strictness is ignored: {@code x > 10} counts as a lower bound of 10.
     */
    public static Optional<ObservableWindow> narrowest(Network network, TestInterface testInterface) {
        Map<Integer, String> observable = new HashMap<>();
        testInterface.inputs().forEach(c -> observable.put(c.channel(), c.modelName()));
        testInterface.outputs().forEach(c -> observable.put(c.channel(), c.modelName()));
        ObservableWindow best = null;
        for (Process process : network.processes()) {
            for (Edge edge : process.edges()) {
                String channel = edge.sync() == null ? null : observable.get(channelIndex(edge.sync().channel()));
                if (channel == null) {
                    continue;
                }
                Map<String, int[]> bounds = new HashMap<>();
                collect(edge.guard(), bounds, true);
                Location source = process.locations().get(edge.source());
                collect(source.invariant(), bounds, false);
                for (Map.Entry<String, int[]> b : bounds.entrySet()) {
                    int[] range = b.getValue();
                    if (range[0] == Integer.MIN_VALUE || range[1] == Integer.MAX_VALUE || range[1] < range[0]) {
                        continue;
                    }
                    ObservableWindow window = new ObservableWindow(channel, process.name(), b.getKey(), range[0],
                            range[1], edge.pos());
                    if (best == null || window.width() < best.width()) {
                        best = window;
                    }
                }
            }
        }
        return Optional.ofNullable(best);
    }

    /** The network index of the channel a sync names, or -1 when it is not a plain channel or constant element. */
    private static int channelIndex(Expression channel) {
        if (channel instanceof Expression.ChannelRef ref) {
            return ref.channel().index();
        }
        if (channel instanceof Expression.Index index && index.array() instanceof Expression.ChannelRef ref
                && index.index() instanceof Expression.Constant element) {
            return ref.channel().index() + element.value();
        }
        return -1;
    }

    /** Adds the constant clock bounds of a conjunction: [lower, upper] by clock; lower ones only from guards. */
    private static void collect(Expression e, Map<String, int[]> bounds, boolean guard) {
        if (e == null) {
            return;
        }
        if (e instanceof Expression.Binary b && b.op() == Expression.Operator.AND) {
            collect(b.left(), bounds, guard);
            collect(b.right(), bounds, guard);
            return;
        }
        if (!(e instanceof Expression.Binary b)) {
            return;
        }
        String clock = clockName(b.left());
        Expression.Operator op = b.op();
        Expression other = b.right();
        if (clock == null) {
            clock = clockName(b.right());
            other = b.left();
            op = flip(op);
        }
        if (clock == null || !(other instanceof Expression.Constant bound) || op == null) {
            return;
        }
        int[] range = bounds.computeIfAbsent(clock, k -> new int[] {Integer.MIN_VALUE, Integer.MAX_VALUE});
        int k = bound.value();
        switch (op) {
            case GE, GT -> {
                if (guard) {
                    range[0] = Math.max(range[0], k);
                }
            }
            case LE, LT -> range[1] = Math.min(range[1], k);
            case EQ -> {
                if (guard) {
                    range[0] = Math.max(range[0], k);
                }
                range[1] = Math.min(range[1], k);
            }
            default -> {
            }
        }
    }

    private static Expression.Operator flip(Expression.Operator op) {
        return switch (op) {
            case LT -> Expression.Operator.GT;
            case LE -> Expression.Operator.GE;
            case GT -> Expression.Operator.LT;
            case GE -> Expression.Operator.LE;
            case EQ -> Expression.Operator.EQ;
            default -> null;
        };
    }

    /** {@code x} or {@code x[2]} for a clock or a constant element of a clock array, else null. */
    private static String clockName(Expression e) {
        if (e instanceof Expression.ClockRef ref && !(ref.type() instanceof io.dtron.model.Type.Array)) {
            return localName(ref.clock());
        }
        if (e instanceof Expression.Index index && index.array() instanceof Expression.ClockRef ref
                && index.index() instanceof Expression.Constant element) {
            return localName(ref.clock()) + "[" + element.value() + "]";
        }
        return null;
    }

    /** A clock's name as its template writes it, without the process's prefix. */
    private static String localName(ClockVariable clock) {
        return clock.name().substring(clock.name().lastIndexOf('.') + 1);
    }
}
