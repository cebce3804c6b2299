package io.dtron.engine.internal.sem;

import io.dtron.model.ChannelVariable;
import io.dtron.model.ClockVariable;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Function;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.Statement;
import io.dtron.model.TestInterface;
import io.dtron.model.Type;
import java.util.ArrayList;
import java.util.BitSet;
import java.util.HashMap;
import java.util.List;
import java.util.Map;

/**
 * The split of a closed network into the environment (what the tester emulates) and the implementation
 * under test (what the tester tracks and checks), by Uppaal TRON's rules: a process that sends an input or
 * receives an output belongs to the environment, one that receives an input or sends an output to the
 * implementation; processes that share an internal channel, or a global variable or clock touched outside an
 * observable synchronisation, are on the same side. Processes linked to neither side are put on the
 * implementation's side.
 */
public final class Partition {
    private final boolean[] environment;
    private final int[] observable;

    private Partition(boolean[] environment, int[] observable) {
        this.environment = environment;
        this.observable = observable;
    }

    /** Channel kinds in {@link #observable(int)}. */
    public static final int INTERNAL = 0;
    /** An input channel (environment to implementation). */
    public static final int INPUT = 1;
    /** An output channel (implementation to environment). */
    public static final int OUTPUT = 2;

    /** Whether process {@code p} is part of the environment. */
    public boolean isEnvironment(int p) {
        return environment[p];
    }

    /** {@link #INPUT}, {@link #OUTPUT} or {@link #INTERNAL} for channel number {@code c}. */
    public int observable(int c) {
        return observable[c];
    }

    /**
     * Splits {@code network} by {@code testInterface}.
     *
     * @throws PartitionException when a process would be on both sides, naming the links that put it there
     */
    public static Partition of(Network network, TestInterface testInterface) {
        int[] kinds = new int[network.channelCount()];
        testInterface.inputs().forEach(c -> kinds[c.channel()] = INPUT);
        testInterface.outputs().forEach(c -> kinds[c.channel()] = OUTPUT);
        int n = network.processes().size();
        int[] parent = new int[n];
        for (int i = 0; i < n; i++) {
            parent[i] = i;
        }
        String[] why = new String[n];
        Boolean[] seed = new Boolean[n];
        Map<String, Integer> firstUser = new HashMap<>();
        for (Process p : network.processes()) {
            Usage usage = new Usage(network);
            for (Location l : p.locations()) {
                if (l.invariant() != null) {
                    usage.touch(l.invariant());
                }
            }
            for (Edge e : p.edges()) {
                BitSet channels = e.sync() == null ? new BitSet() : channelsOf(e.sync().channel());
                boolean observableSync = false;
                for (int c = channels.nextSetBit(0); c >= 0; c = channels.nextSetBit(c + 1)) {
                    if (kinds[c] == INTERNAL) {
                        usage.names.add("channel " + network.channelName(c));
                        continue;
                    }
                    observableSync = true;
                    boolean send = e.sync().direction() == Edge.Direction.SEND;
                    boolean env = kinds[c] == INPUT ? send : !send;
                    String reason = (send ? "sends " : "receives ") + (kinds[c] == INPUT ? "input " : "output ")
                            + network.channelName(c);
                    if (seed[p.index()] != null && seed[p.index()] != env) {
                        throw new PartitionException("process " + p.name() + " " + reason + " but also " + why[p.index()]
                                + ": it would be both environment and implementation");
                    }
                    seed[p.index()] = env;
                    why[p.index()] = reason;
                }
                if (!observableSync) {
                    if (e.guard() != null) {
                        usage.touch(e.guard());
                    }
                    e.updates().forEach(usage::touch);
                    if (e.sync() != null) {
                        usage.touch(e.sync().channel());
                    }
                }
            }
            for (String name : usage.names) {
                Integer other = firstUser.putIfAbsent(name, p.index());
                if (other != null) {
                    union(parent, other, p.index());
                }
            }
        }
        Boolean[] classSide = new Boolean[n];
        String[] classWhy = new String[n];
        for (int p = 0; p < n; p++) {
            if (seed[p] == null) {
                continue;
            }
            int root = find(parent, p);
            if (classSide[root] != null && !classSide[root].equals(seed[p])) {
                throw new PartitionException("process " + network.processes().get(p).name() + " " + why[p]
                        + ", but it shares internal channels or variables with a process that " + classWhy[root]
                        + ": they would be on both sides");
            }
            classSide[root] = seed[p];
            classWhy[root] = network.processes().get(p).name() + " " + why[p];
        }
        boolean[] environment = new boolean[n];
        for (int p = 0; p < n; p++) {
            Boolean side = classSide[find(parent, p)];
            environment[p] = side != null && side;
        }
        return new Partition(environment, kinds);
    }

    /** The names of the processes on each side, for messages. */
    public List<String> names(Network network, boolean env) {
        List<String> out = new ArrayList<>();
        for (Process p : network.processes()) {
            if (environment[p.index()] == env) {
                out.add(p.name());
            }
        }
        return out;
    }

    private static int find(int[] parent, int i) {
        while (parent[i] != i) {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    }

    private static void union(int[] parent, int a, int b) {
        parent[find(parent, a)] = find(parent, b);
    }

    /** The channels a synchronisation's channel expression may denote (all of an array for a variable index). */
    static BitSet channelsOf(Expression e) {
        BitSet out = new BitSet();
        int[] range = range(e);
        if (range != null) {
            out.set(range[0], range[1]);
        }
        return out;
    }

    private static int[] range(Expression e) {
        if (e instanceof Expression.ChannelRef c) {
            ChannelVariable v = c.channel();
            return new int[] {v.index(), v.index() + v.type().channels()};
        }
        if (e instanceof Expression.Index i && i.array().type() instanceof Type.Array a) {
            int[] outer = range(i.array());
            if (outer == null) {
                return null;
            }
            int size = a.element().channels();
            if (i.index() instanceof Expression.Constant k) {
                int start = outer[0] + (k.value() - a.firstIndex()) * size;
                return new int[] {start, start + size};
            }
            return outer;
        }
        return null;
    }

    /** The global variables and clocks an expression, statement or called function touches. */
    private static final class Usage {
        private final Network network;
        final java.util.Set<String> names = new java.util.LinkedHashSet<>();
        private final BitSet visitedFunctions = new BitSet();

        Usage(Network network) {
            this.network = network;
        }

        void touch(Expression e) {
            if (e instanceof Expression.VariableRef v) {
                if (v.variable().owner() == null) {
                    names.add("variable " + v.variable().name());
                }
            } else if (e instanceof Expression.ClockRef c) {
                ClockVariable clock = c.clock();
                if (clock.owner() == null) {
                    names.add("clock " + clock.name());
                }
            } else if (e instanceof Expression.Index i) {
                touch(i.array());
                touch(i.index());
            } else if (e instanceof Expression.FieldRef f) {
                touch(f.struct());
            } else if (e instanceof Expression.Unary u) {
                touch(u.operand());
            } else if (e instanceof Expression.Binary b) {
                touch(b.left());
                touch(b.right());
            } else if (e instanceof Expression.Conditional c) {
                touch(c.condition());
                touch(c.then());
                touch(c.otherwise());
            } else if (e instanceof Expression.Assign a) {
                touch(a.target());
                touch(a.value());
            } else if (e instanceof Expression.Increment i) {
                touch(i.target());
            } else if (e instanceof Expression.Quantified q) {
                touch(q.body());
            } else if (e instanceof Expression.ClockRate r) {
                touch(r.clock());
                touch(r.rate());
            } else if (e instanceof Expression.Call c) {
                c.args().forEach(this::touch);
                if (!visitedFunctions.get(c.function())) {
                    visitedFunctions.set(c.function());
                    Function f = network.functions().get(c.function());
                    touch(f.body());
                }
            }
        }

        void touch(Statement s) {
            if (s instanceof Statement.Block b) {
                b.statements().forEach(this::touch);
            } else if (s instanceof Statement.Eval e) {
                touch(e.expression());
            } else if (s instanceof Statement.InitLocal l) {
                if (l.initial() != null) {
                    touch(l.initial());
                }
            } else if (s instanceof Statement.If i) {
                touch(i.condition());
                touch(i.then());
                if (i.otherwise() != null) {
                    touch(i.otherwise());
                }
            } else if (s instanceof Statement.While w) {
                touch(w.condition());
                touch(w.body());
            } else if (s instanceof Statement.DoWhile d) {
                touch(d.body());
                touch(d.condition());
            } else if (s instanceof Statement.For f) {
                f.init().forEach(this::touch);
                if (f.condition() != null) {
                    touch(f.condition());
                }
                f.step().forEach(this::touch);
                touch(f.body());
            } else if (s instanceof Statement.Iterate i) {
                touch(i.body());
            } else if (s instanceof Statement.Return r) {
                if (r.value() != null) {
                    touch(r.value());
                }
            } else if (s instanceof Statement.Assert a) {
                touch(a.condition());
            }
        }
    }
}
