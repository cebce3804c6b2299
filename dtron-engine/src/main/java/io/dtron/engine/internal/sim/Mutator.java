package io.dtron.engine.internal.sim;

import io.dtron.engine.sim.Mutant;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import io.dtron.model.Type;
import io.dtron.xta.Pos;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Set;

/**
 * Derives the mutants of the processes on the implementation's side of a network, each a copy of the network with
 * one change: a bound of a guard or invariant moved by one, an output edge made never enabled or shifted a time
 * unit earlier or later, a wrong value for a variable attached to an output, an urgent or committed location made
 * ordinary.
 */
public final class Mutator {
    private final Network network;
    private final boolean[] inside;
    private final TestInterface testInterface;
    private final List<Change> out = new ArrayList<>();

    /**
     * One change.
     *
     * @param kind     its kind
     * @param process  the process changed
     * @param location the location the change takes effect at (an edge's source), for the reachability of it
     * @param change   what changed, as text
     * @param pos      where
     * @param network  the changed network
     */
    public record Change(Mutant.Kind kind, Process process, Location location, String change, Pos pos,
                         Network network) {
    }

    private Mutator(Network network, boolean[] inside, TestInterface testInterface) {
        this.network = network;
        this.inside = inside;
        this.testInterface = testInterface;
    }

    /** The changes of the processes {@code inside} marks, in process, location and edge order. */
    public static List<Change> changes(Network network, boolean[] inside, TestInterface testInterface) {
        Mutator m = new Mutator(network, inside, testInterface);
        for (Process p : network.processes()) {
            if (inside[p.index()]) {
                m.process(p);
            }
        }
        return m.out;
    }

    private void process(Process p) {
        for (Location l : p.locations()) {
            if (l.invariant() != null) {
                for (Expression atom : atoms(l.invariant(), true)) {
                    for (int d : new int[] {-1, 1}) {
                        Expression inv = replace(l.invariant(), atom, shifted(atom, d));
                        add(Mutant.Kind.INVARIANT_BOUND, p, l, p.name() + "." + l.name() + ": " + describe(atom, d),
                                atom.pos(),
                                withLocation(p, withInvariant(l, inv)));
                    }
                }
            }
            if (l.kind() == Location.Kind.URGENT || l.kind() == Location.Kind.COMMITTED) {
                add(Mutant.Kind.URGENCY_REMOVED, p, l, p.name() + "." + l.name() + " "
                        + l.kind().name().toLowerCase(java.util.Locale.ROOT) + " -> ordinary", l.pos(),
                        withLocation(p, new Location(l.index(), l.name(), Location.Kind.NORMAL, l.invariant(),
                                l.frameSize(), l.pos())));
            }
        }
        for (Edge e : p.edges()) {
            Location source = p.locations().get(e.source());
            String edgeName = p.name() + ": " + source.name() + " -> " + p.locations().get(e.target()).name();
            if (e.guard() != null) {
                for (Expression atom : atoms(e.guard(), false)) {
                    for (int d : new int[] {-1, 1}) {
                        add(Mutant.Kind.GUARD_BOUND, p, source, edgeName + ": " + describe(atom, d), atom.pos(),
                                withEdge(p, withGuard(e, replace(e.guard(), atom, shifted(atom, d)))));
                    }
                }
            }
            TestInterface.ObservableChannel output = outputOf(e);
            if (output == null) {
                continue;
            }
            String edge = edgeName + " " + e.sync().channel().pos().text() + "!";
            add(Mutant.Kind.OUTPUT_DROPPED, p, source, edge + " never enabled", e.pos(),
                    withEdge(p, withGuard(e, new Expression.Constant(e.pos(), Type.Bool.INSTANCE, 0))));
            List<Expression> guardAtoms = e.guard() == null ? List.of() : atoms(e.guard(), true);
            List<Expression> invariantAtoms = source.invariant() == null ? List.of() : atoms(source.invariant(), true);
            if (!guardAtoms.isEmpty() || !invariantAtoms.isEmpty()) {
                for (int d : new int[] {-1, 1}) {
                    Expression guard = e.guard();
                    for (Expression atom : guardAtoms) {
                        guard = replace(guard, atom, shifted(atom, d));
                    }
                    Expression inv = source.invariant();
                    for (Expression atom : invariantAtoms) {
                        inv = replace(inv, atom, shifted(atom, d));
                    }
                    Process changed = withEdge(p, withGuard(e, guard));
                    changed = withLocation(changed, withInvariant(source, inv));
                    add(d < 0 ? Mutant.Kind.OUTPUT_EARLY : Mutant.Kind.OUTPUT_LATE, p, source, edge + ": its clock"
                            + " bounds " + (d < 0 ? "1 earlier" : "1 later"), e.pos(), changed);
                }
            }
            Set<Integer> attached = new HashSet<>();
            output.variables().forEach(v -> attached.add(v.variable().offset()));
            for (int i = 0; i < e.updates().size(); i++) {
                Expression u = e.updates().get(i);
                if (u instanceof Expression.Assign a && a.target() instanceof Expression.VariableRef ref
                        && attached.contains(ref.variable().offset()) && ref.variable().type() instanceof Type.Int t
                        && t.lower() < t.upper()) {
                    List<Expression> updates = new ArrayList<>(e.updates());
                    updates.set(i, new Expression.Assign(a.pos(), a.type(), a.target(), a.op(), wrong(a.value(), t)));
                    add(Mutant.Kind.OUTPUT_VALUE, p, source, edge + ": " + a.pos().text() + " -> "
                            + ref.variable().name() + " one off", a.pos(), withEdge(p, new Edge(e.index(), e.source(), e.target(),
                            e.selects(), e.guard(), e.sync(), updates, e.frameSize(), e.pos())));
                }
            }
        }
    }

    private void add(Mutant.Kind kind, Process original, Location location, String change, Pos pos,
                     Process changed) {
        List<Process> processes = new ArrayList<>(network.processes());
        processes.set(changed.index(), changed);
        Network n = new Network(network.file(), processes, network.variables(), network.clocks(), network.channels(),
                network.functions(), network.stateSize(), network.clockCount(), network.channelCount(),
                network.channelPriority(), network.queries(), network.warnings(), network.startErrors());
        out.add(new Change(kind, original, location, change, pos, n));
    }

    /** The output of the interface that edge {@code e} sends, or null. */
    private TestInterface.ObservableChannel outputOf(Edge e) {
        if (e.sync() == null || e.sync().direction() != Edge.Direction.SEND
                || !(e.sync().channel() instanceof Expression.ChannelRef ref)) {
            return null;
        }
        return testInterface.outputs().stream().filter(o -> o.channel() == ref.channel().index()).findFirst()
                .orElse(null);
    }

    // ================================================================ expressions

    /**
     * The comparisons of a conjunction that bound a clock (the other side is the bound), and unless {@code
     * clocksOnly} those that compare data with a constant.
     */
    static List<Expression> atoms(Expression e, boolean clocksOnly) {
        List<Expression> found = new ArrayList<>();
        collect(e, clocksOnly, found);
        return found;
    }

    private static void collect(Expression e, boolean clocksOnly, List<Expression> found) {
        if (!(e instanceof Expression.Binary b)) {
            return;
        }
        switch (b.op()) {
            case AND -> {
                collect(b.left(), clocksOnly, found);
                collect(b.right(), clocksOnly, found);
            }
            case LT, LE, EQ, GE, GT -> {
                if (bound(b, clocksOnly) != null) {
                    found.add(b);
                }
            }
            default -> {
            }
        }
    }

    /** The side of comparison {@code b} that is its bound, or null. */
    private static Expression bound(Expression.Binary b, boolean clocksOnly) {
        boolean leftClock = isClock(b.left().type());
        boolean rightClock = isClock(b.right().type());
        if (leftClock != rightClock) {
            Expression side = leftClock ? b.right() : b.left();
            return side.type() instanceof Type.Int ? side : null;
        }
        if (leftClock || clocksOnly) {
            return null;
        }
        if (b.right() instanceof Expression.Constant) {
            return b.right();
        }
        return b.left() instanceof Expression.Constant ? b.left() : null;
    }

    private static boolean isClock(Type t) {
        return t instanceof Type.Clock || t instanceof Type.ClockDifference;
    }

    /** Comparison {@code atom} with its bound moved by {@code d}. */
    private static Expression shifted(Expression atom, int d) {
        Expression.Binary b = (Expression.Binary) atom;
        Expression bound = bound(b, false);
        Expression moved = plus(bound, d);
        return bound == b.right() ? new Expression.Binary(b.pos(), b.type(), b.op(), b.left(), moved)
                : new Expression.Binary(b.pos(), b.type(), b.op(), moved, b.right());
    }

    private static Expression plus(Expression e, int d) {
        if (e instanceof Expression.Constant c) {
            return new Expression.Constant(c.pos(), Type.Int.DEFAULT, c.value() + d);
        }
        return new Expression.Binary(e.pos(), Type.Int.DEFAULT, d < 0 ? Expression.Operator.SUB
                : Expression.Operator.ADD, e, new Expression.Constant(e.pos(), Type.Int.DEFAULT, Math.abs(d)));
    }

    /** A value one off {@code value}, kept in {@code range}: one more, or one less at the top of the range. */
    private static Expression wrong(Expression value, Type.Int range) {
        Expression up = plus(value, 1);
        Expression fits = new Expression.Binary(value.pos(), Type.Bool.INSTANCE, Expression.Operator.LE, up,
                new Expression.Constant(value.pos(), Type.Int.DEFAULT, range.upper()));
        return new Expression.Conditional(value.pos(), Type.Int.DEFAULT, fits, up, plus(value, -1));
    }

    /** {@code root} with {@code target} (by identity) replaced by {@code replacement}. */
    private static Expression replace(Expression root, Expression target, Expression replacement) {
        if (root == target) {
            return replacement;
        }
        if (root instanceof Expression.Binary b) {
            Expression l = replace(b.left(), target, replacement);
            Expression r = replace(b.right(), target, replacement);
            return l == b.left() && r == b.right() ? b : new Expression.Binary(b.pos(), b.type(), b.op(), l, r);
        }
        return root;
    }

    /** {@code atom} and its text with the bound moved by {@code d}: {@code x <= 5 -> x <= 6}. */
    private static String describe(Expression atom, int d) {
        Expression.Binary b = (Expression.Binary) atom;
        Expression bound = bound(b, false);
        String text = b.pos().text();
        int from = bound.pos().start() - b.pos().start();
        int to = bound.pos().end() - b.pos().start();
        String boundText = bound instanceof Expression.Constant c ? String.valueOf(c.value() + d)
                : "(" + bound.pos().text() + ") " + (d < 0 ? "- 1" : "+ 1");
        if (bound.pos().fragment() != b.pos().fragment() || from < 0 || to > text.length() || from > to) {
            return text + ", bound " + (d < 0 ? "- 1" : "+ 1");
        }
        return text + " -> " + text.substring(0, from) + boundText + text.substring(to);
    }

    private static Edge withGuard(Edge e, Expression guard) {
        return new Edge(e.index(), e.source(), e.target(), e.selects(), guard, e.sync(), e.updates(), e.frameSize(),
                e.pos());
    }

    private static Location withInvariant(Location l, Expression invariant) {
        return new Location(l.index(), l.name(), l.kind(), invariant, l.frameSize(), l.pos());
    }

    private static Process withEdge(Process p, Edge e) {
        List<Edge> edges = new ArrayList<>(p.edges());
        edges.set(e.index(), e);
        return new Process(p.index(), p.name(), p.template(), p.locations(), p.initial(), edges, p.priority());
    }

    private static Process withLocation(Process p, Location l) {
        List<Location> locations = new ArrayList<>(p.locations());
        locations.set(l.index(), l);
        return new Process(p.index(), p.name(), p.template(), locations, p.initial(), p.edges(), p.priority());
    }
}
