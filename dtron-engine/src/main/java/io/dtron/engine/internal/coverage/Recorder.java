package io.dtron.engine.internal.coverage;

import io.dtron.engine.Event;
import io.dtron.engine.coverage.Coverage;
import io.dtron.engine.coverage.RunCoverage;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.tester.StateSet;
import io.dtron.engine.internal.verify.Coverable;
import io.dtron.model.Edge;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import java.nio.charset.StandardCharsets;
import java.security.MessageDigest;
import java.security.NoSuchAlgorithmException;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.BitSet;
import java.util.Collection;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.function.Consumer;

/**
 * Records what a run covers, on the tester's thread. Edges and locations have one number each across the network
 * ({@code base[process] + index}). For every event the tester judges allowed, {@link #step} says which edges its
 * move took for certain (every state the tester keeps after it took the edge) and possibly (some did, or the
 * closure of delays and internal moves before it followed the edge); {@link #commit} adds a step once the tester
 * has committed to its event, with the locations, traps and channel values it shows.
 */
public final class Recorder implements RunCoverage {
    private static final byte NO = 0;
    private static final byte POSSIBLY = 1;
    private static final byte CERTAINLY = 2;

    private final Network network;
    private final Partition partition;
    private final Coverable coverable;
    private final long seed;
    private final int[] edgeBase;
    private final int[] locationBase;
    private final int[] edgeProcess;
    private final byte[] edgeTaken;
    private final byte[] locationTaken;
    private final List<String> trapNames = new ArrayList<>();
    private final int[] trapSlots;
    private final byte[] trapTaken;
    private final Map<String, Channel> channels = new LinkedHashMap<>();
    private int edgesCovered;
    private int edgesCoverable;
    private int locationsCovered;
    private int locationsCoverable;
    private int trapsSet;
    /** The internal edges the closure before the event being judged followed. */
    private final BitSet closure = new BitSet();
    private final Consumer<Semantics.Move> internalMoves = this::internalMove;
    /** Per edge, how many of the successors being summed up took it (scratch of {@link #step}). */
    private final int[] counts;
    /** The edges {@link #counts} counts, and those taken for certain (scratch of {@link #step}). */
    private final int[] touched;
    private final BitSet certain = new BitSet();
    /**
     * Per process and location, the one edge that may leave it (or enter it) without an observable channel, or -1
     * when there are none or several: a process the closure moved away from (or into) the location took it.
     */
    private final int[][] uniqueOut;
    private final int[][] uniqueIn;

    /**
     * What one event took: edge numbers taken for certain and possibly (not for certain).
     *
     * @param certainly edges every successor took
     * @param possibly  edges some successor, or the closure before it, took
     */
    public record Step(int[] certainly, int[] possibly) {
    }

    /** What is known of one channel. */
    private static final class Channel {
        final boolean input;
        long count;
        final Set<Map<String, Integer>> values = new LinkedHashSet<>();
        boolean more;

        Channel(boolean input) {
            this.input = input;
        }
    }

    /**
     * A recorder for one run of {@code network}, split by {@code partition}, measured against {@code coverable}.
     * Traps are the bool variables and arrays whose name (without its process) starts with {@code trap} or
     * {@code t_}, and those named in {@code trapNames} (qualified or not).
     */
    public Recorder(Network network, Partition partition, TestInterface testInterface, Coverable coverable,
                    long seed, Collection<String> extraTraps) {
        this.network = network;
        this.partition = partition;
        this.coverable = coverable;
        this.seed = seed;
        int n = network.processes().size();
        edgeBase = new int[n + 1];
        locationBase = new int[n + 1];
        for (Process p : network.processes()) {
            edgeBase[p.index() + 1] = edgeBase[p.index()] + p.edges().size();
            locationBase[p.index() + 1] = locationBase[p.index()] + p.locations().size();
        }
        edgeProcess = new int[edgeBase[n]];
        for (Process p : network.processes()) {
            Arrays.fill(edgeProcess, edgeBase[p.index()], edgeBase[p.index() + 1], p.index());
            for (Edge e : p.edges()) {
                edgesCoverable += coverable.edge(p.index(), e.index()) ? 1 : 0;
            }
            for (Location l : p.locations()) {
                locationsCoverable += coverable.location(p.index(), l.index()) ? 1 : 0;
            }
        }
        uniqueOut = new int[n][];
        uniqueIn = new int[n][];
        for (Process p : network.processes()) {
            uniqueOut[p.index()] = new int[p.locations().size()];
            uniqueIn[p.index()] = new int[p.locations().size()];
            Arrays.fill(uniqueOut[p.index()], -1);
            Arrays.fill(uniqueIn[p.index()], -1);
            int[] outs = new int[p.locations().size()];
            int[] ins = new int[p.locations().size()];
            for (Edge e : p.edges()) {
                if (!surelyObservable(network, partition, e)) {
                    outs[e.source()]++;
                    ins[e.target()]++;
                    uniqueOut[p.index()][e.source()] = e.index();
                    uniqueIn[p.index()][e.target()] = e.index();
                }
            }
            for (int l = 0; l < outs.length; l++) {
                uniqueOut[p.index()][l] = outs[l] == 1 ? uniqueOut[p.index()][l] : -1;
                uniqueIn[p.index()][l] = ins[l] == 1 ? uniqueIn[p.index()][l] : -1;
            }
        }
        edgeTaken = new byte[edgeBase[n]];
        locationTaken = new byte[locationBase[n]];
        counts = new int[edgeBase[n]];
        touched = new int[edgeBase[n]];
        List<Integer> slots = new ArrayList<>();
        traps(network, extraTraps, trapNames, slots);
        trapSlots = slots.stream().mapToInt(Integer::intValue).toArray();
        trapTaken = new byte[trapSlots.length];
        for (TestInterface.ObservableChannel c : testInterface.inputs()) {
            channels.put(c.name(), new Channel(true));
        }
        for (TestInterface.ObservableChannel c : testInterface.outputs()) {
            channels.put(c.name(), new Channel(false));
        }
    }

    /** The names in {@code names} that are not bool variables or arrays of the model: for an error. */
    public static List<String> notTraps(Network network, Collection<String> names) {
        List<String> out = new ArrayList<>();
        for (String name : names) {
            boolean found = false;
            for (Variable v : network.variables()) {
                String simple = v.name().substring(v.name().lastIndexOf('.') + 1);
                found |= (v.name().equals(name) || simple.equals(name)) && isBool(v.type());
            }
            if (!found) {
                out.add(name);
            }
        }
        return out;
    }

    private static boolean isBool(Type t) {
        while (t instanceof Type.Array a) {
            t = a.element();
        }
        return t instanceof Type.Bool;
    }

    /** The trap names of {@code network}, in state-vector order (see {@link io.dtron.engine.coverage.Traps}). */
    public static List<String> trapNames(Network network, Collection<String> extraTraps) {
        List<String> names = new ArrayList<>();
        traps(network, extraTraps, names, new ArrayList<>());
        return names;
    }

    private static void traps(Network network, Collection<String> extraTraps, List<String> names,
                              List<Integer> slots) {
        for (Variable v : network.variables()) {
            String simple = v.name().substring(v.name().lastIndexOf('.') + 1);
            boolean named = extraTraps.contains(v.name()) || extraTraps.contains(simple)
                    || simple.startsWith("trap") || simple.startsWith("t_");
            if (named && isBool(v.type())) {
                elements(v.name(), v.type(), v.offset(), names, slots);
            }
        }
    }

    private static void elements(String name, Type type, int offset, List<String> names, List<Integer> slots) {
        if (type instanceof Type.Array a) {
            int size = a.element().slots();
            for (int i = 0; i < a.length(); i++) {
                elements(name + "[" + (a.firstIndex() + i) + "]", a.element(), offset + i * size, names, slots);
            }
        } else {
            names.add(name);
            slots.add(offset);
        }
    }

    /** Records the initial state: its locations are visited, its traps may be set. */
    public void start(StateSet initial) {
        states(initial.states());
    }

    /** The sink for the internal moves of the closure before the next event: call {@link #begin} first. */
    public Consumer<Semantics.Move> internalMoves() {
        return internalMoves;
    }

    /** Starts the judgement of an event: forgets the closure of the last one. */
    public void begin() {
        closure.clear();
    }

    private void internalMove(Semantics.Move move) {
        for (Semantics.Step s : move.steps()) {
            closure.set(edgeBase[s.process()] + s.edge().index());
        }
    }

    /**
     * Whether {@code e} synchronises on a channel every element of which is an input or an output: the closure of
     * delays and internal moves never takes it. When its channel cannot be told from the text (an array element
     * chosen by an expression), no.
     */
    private static boolean surelyObservable(Network network, Partition partition, Edge e) {
        if (e.sync() == null || e.sync().channel().pos() == null) {
            return false;
        }
        var channel = network.channel(e.sync().channel().pos().text().trim());
        if (channel.isEmpty()) {
            return false;
        }
        int count = Math.max(1, channel.get().type().channels());
        for (int c = channel.get().index(); c < channel.get().index() + count; c++) {
            if (partition.observable(c) == Partition.INTERNAL) {
                return false;
            }
        }
        return true;
    }

    /**
     * What the event judged since {@link #begin} took, given the states {@code before} it (at the last event) and
     * the moves of the successors the tester keeps. Besides the edges of every successor's move, an internal edge
     * is taken for certain when a process was in one location in every state before and in another in every state
     * the move starts from, and the edge is the only one that leaves the first (or enters the second) without an
     * observable channel, or the only one along such a chain.
     */
    public Step step(List<SymState> before, List<StateSet.Successor> successors) {
        int n = 0;
        for (StateSet.Successor s : successors) {
            for (Semantics.Step st : s.move().steps()) {
                int id = edgeBase[st.process()] + st.edge().index();
                if (counts[id]++ == 0) {
                    touched[n++] = id;
                }
            }
        }
        certain.clear();
        for (int t = 0; t < n; t++) {
            int id = touched[t];
            if (counts[id] == successors.size()) {
                certain.set(id);
            } else {
                closure.set(id);
            }
            counts[id] = 0;
        }
        internalChains(before, successors, certain);
        closure.andNot(certain);
        return new Step(ids(certain), ids(closure));
    }

    /** The set bits of {@code bits}, in order. */
    private static int[] ids(BitSet bits) {
        int[] out = new int[bits.cardinality()];
        for (int i = bits.nextSetBit(0), k = 0; i >= 0; i = bits.nextSetBit(i + 1)) {
            out[k++] = i;
        }
        return out;
    }

    /**
     * Adds to {@code out} the internal edges every path of the closure took, by the locations before it and where
     * the move starts.
     */
    private void internalChains(List<SymState> before, List<StateSet.Successor> successors, BitSet out) {
        if (before.isEmpty() || successors.isEmpty()) {
            return;
        }
        for (int p = 0; p < uniqueOut.length; p++) {
            int l0 = before.get(0).location(p);
            int l1 = successors.get(0).from().location(p);
            if (l0 < 0 || l1 < 0 || l0 == l1) {
                continue;
            }
            boolean same = true;
            for (SymState s : before) {
                same &= s.location(p) == l0;
            }
            for (StateSet.Successor s : successors) {
                same &= s.from().location(p) == l1;
            }
            if (!same) {
                continue;
            }
            List<Edge> edges = network.processes().get(p).edges();
            // forward from l0: the process left each location of the chain, by its one internal edge
            BitSet seen = new BitSet();
            for (int l = l0; l != l1 && !seen.get(l) && uniqueOut[p][l] >= 0; l = edges.get(uniqueOut[p][l]).target()) {
                seen.set(l);
                out.set(edgeBase[p] + uniqueOut[p][l]);
            }
            // backward from l1: it entered each location of the chain by its one internal edge
            seen.clear();
            for (int l = l1; l != l0 && !seen.get(l) && uniqueIn[p][l] >= 0; l = edges.get(uniqueIn[p][l]).source()) {
                seen.set(l);
                out.set(edgeBase[p] + uniqueIn[p][l]);
            }
        }
    }

    /**
     * Adds {@code step}, the step of {@code event} (an input when {@code input}), after which the tester keeps
     * {@code after}.
     */
    public void commit(Step step, Event event, boolean input, StateSet after) {
        for (int id : step.certainly()) {
            takeEdge(id, CERTAINLY);
        }
        for (int id : step.possibly()) {
            takeEdge(id, POSSIBLY);
        }
        states(after.states());
        Channel ch = channels.get(event.channel());
        if (ch != null) {
            ch.count++;
            if (!ch.values.contains(event.values())) {
                if (ch.values.size() < Coverage.ChannelCoverage.MAX_VALUES) {
                    ch.values.add(event.values());
                } else {
                    ch.more = true;
                }
            }
        }
    }

    private void takeEdge(int id, byte how) {
        int p = edgeProcess[id];
        Edge e = network.processes().get(p).edges().get(id - edgeBase[p]);
        if (edgeTaken[id] < how) {
            if (how == CERTAINLY && coverable.edge(p, e.index())) {
                edgesCovered++;
            }
            edgeTaken[id] = how;
        }
        // the process was in the edge's source and went to its target: both as certain as the edge
        visit(p, e.source(), how);
        visit(p, e.target(), how);
    }

    private void visit(int p, int l, byte how) {
        int id = locationBase[p] + l;
        if (locationTaken[id] < how) {
            if (how == CERTAINLY && coverable.location(p, l)) {
                locationsCovered++;
            }
            locationTaken[id] = how;
        }
    }

    /** The locations (every state's, for certain those all share) and traps of a set the tester keeps. */
    private void states(List<SymState> states) {
        if (states.isEmpty()) {
            return;
        }
        int n = network.processes().size();
        SymState first = states.get(0);
        for (int p = 0; p < n; p++) {
            int l = first.location(p);
            boolean same = l >= 0;
            for (SymState s : states) {
                if (s.location(p) >= 0) {
                    visit(p, s.location(p), POSSIBLY);
                }
                same &= s.location(p) == l;
            }
            if (same) {
                visit(p, l, CERTAINLY);
            }
        }
        for (int t = 0; t < trapSlots.length; t++) {
            if (trapTaken[t] == CERTAINLY) {
                continue;
            }
            int set = 0;
            for (SymState s : states) {
                set += s.var(trapSlots[t]) != 0 ? 1 : 0;
            }
            byte how = set == states.size() ? CERTAINLY : set > 0 ? POSSIBLY : NO;
            if (how > trapTaken[t]) {
                trapsSet += how == CERTAINLY ? 1 : 0;
                trapTaken[t] = how;
            }
        }
    }

    /** The edges of {@code ids} as people read them: {@code Lamp: off -> low i_press?}. */
    public List<String> describe(int[] ids) {
        List<String> out = new ArrayList<>(ids.length);
        for (int id : ids) {
            Process p = network.processes().get(edgeProcess[id]);
            Edge e = p.edges().get(id - edgeBase[p.index()]);
            String label = label(e);
            out.add(p.name() + ": " + p.locations().get(e.source()).name() + " -> "
                    + p.locations().get(e.target()).name() + (label.isEmpty() ? "" : " " + label));
        }
        return out;
    }

    @Override
    public boolean edgeTaken(int process, int edge) {
        return edgeTaken[edgeBase[process] + edge] == CERTAINLY;
    }

    @Override
    public boolean edgePossiblyTaken(int process, int edge) {
        return edgeTaken[edgeBase[process] + edge] != NO;
    }

    @Override
    public boolean locationVisited(int process, int location) {
        return locationTaken[locationBase[process] + location] == CERTAINLY;
    }

    @Override
    public boolean edgeCoverable(int process, int edge) {
        return coverable.edge(process, edge);
    }

    @Override
    public boolean locationCoverable(int process, int location) {
        return coverable.location(process, location);
    }

    @Override
    public List<String> trapNames() {
        return List.copyOf(trapNames);
    }

    @Override
    public boolean trapSet(int trap) {
        return trapTaken[trap] == CERTAINLY;
    }

    @Override
    public Coverage.Figure edges() {
        return new Coverage.Figure(edgesCovered, edgesCoverable);
    }

    @Override
    public Coverage.Figure locations() {
        return new Coverage.Figure(locationsCovered, locationsCoverable);
    }

    @Override
    public Coverage.Figure traps() {
        return new Coverage.Figure(trapsSet, trapSlots.length);
    }

    @Override
    public Coverage snapshot() {
        List<Coverage.ProcessCoverage> processes = new ArrayList<>();
        for (Process p : network.processes()) {
            List<Coverage.LocationCoverage> locations = new ArrayList<>();
            for (Location l : p.locations()) {
                locations.add(new Coverage.LocationCoverage(l.name(), l.pos() == null ? 0 : l.pos().line(),
                        reach(coverable.locationReached(p.index(), l.index())),
                        taken(locationTaken[locationBase[p.index()] + l.index()])));
            }
            List<Coverage.EdgeCoverage> edges = new ArrayList<>();
            for (Edge e : p.edges()) {
                edges.add(new Coverage.EdgeCoverage(e.index(), p.locations().get(e.source()).name(),
                        p.locations().get(e.target()).name(), label(e), e.pos() == null ? 0 : e.pos().line(),
                        reach(coverable.edgeReached(p.index(), e.index())),
                        taken(edgeTaken[edgeBase[p.index()] + e.index()])));
            }
            processes.add(new Coverage.ProcessCoverage(p.name(), p.template(), partition.isEnvironment(p.index()),
                    locations, edges));
        }
        List<Coverage.Trap> traps = new ArrayList<>();
        for (int t = 0; t < trapSlots.length; t++) {
            traps.add(new Coverage.Trap(trapNames.get(t), taken(trapTaken[t])));
        }
        List<Coverage.ChannelCoverage> chans = new ArrayList<>();
        channels.forEach((name, c) -> chans.add(new Coverage.ChannelCoverage(name, c.input, c.count,
                new ArrayList<>(c.values), c.more)));
        return new Coverage(network.file(), fingerprint(network), List.of(seed), processes, traps, chans,
                coverable.stopped());
    }

    private Coverage.Reach reach(boolean reached) {
        return reached ? Coverage.Reach.REACHABLE : coverable.stopped() != null ? Coverage.Reach.UNKNOWN
                : Coverage.Reach.UNREACHABLE;
    }

    private static Coverage.Taken taken(byte b) {
        return b == CERTAINLY ? Coverage.Taken.CERTAINLY : b == POSSIBLY ? Coverage.Taken.POSSIBLY : Coverage.Taken.NO;
    }

    /** The synchronisation of {@code e} as written ({@code i_press?}), or empty. */
    private static String label(Edge e) {
        if (e.sync() == null) {
            return "";
        }
        String channel = e.sync().channel().pos() == null ? "" : e.sync().channel().pos().text();
        return channel + switch (e.sync().direction()) {
            case SEND -> "!";
            case RECEIVE -> "?";
            case CSP -> "";
        };
    }

    /**
     * A digest of the model's shape: its processes, their templates, locations and edges (source, target, label).
     * Two runs of one model file agree; a changed model does not.
     */
    public static String fingerprint(Network network) {
        StringBuilder sb = new StringBuilder();
        for (Process p : network.processes()) {
            sb.append(p.name()).append('/').append(p.template()).append('{');
            for (Location l : p.locations()) {
                sb.append(l.name()).append(',');
            }
            sb.append('|');
            for (Edge e : p.edges()) {
                sb.append(e.source()).append('>').append(e.target()).append(label(e)).append(',');
            }
            sb.append('}');
        }
        try {
            byte[] d = MessageDigest.getInstance("SHA-256").digest(sb.toString().getBytes(StandardCharsets.UTF_8));
            StringBuilder hex = new StringBuilder();
            for (int i = 0; i < 8; i++) {
                hex.append(String.format(Locale.ROOT, "%02x", d[i]));
            }
            return hex.toString();
        } catch (NoSuchAlgorithmException e) {
            throw new IllegalStateException(e);
        }
    }
}
