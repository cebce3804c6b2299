package io.dtron.engine.internal.sem;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.eval.ClockBounds;
import io.dtron.engine.internal.eval.ClockResets;
import io.dtron.engine.internal.eval.Evaluator;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.Type;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

/**
 * The symbolic semantics of a network, as Uppaal defines it: internal moves, binary synchronisation (the
 * sender's updates before the receiver's), broadcast synchronisation (every process with an enabled receiving
 * edge takes part, in the order of the system line), committed locations (a move must involve a process in a
 * committed location when there is one), urgent locations and urgent channels (no delay), select bindings,
 * guards on data and clocks, and location invariants bounding delays. Zones are over integer ticks, a fixed
 * number per model time unit; unless made without it, the last clock of every zone is the tester's clock of time
 * elapsed since its last observation.
 */
public final class Semantics {
    private final Network network;
    private final Evaluator evaluator;
    private final int ticksPerUnit;
    private final int dimension;
    private final int[] maxBounds;
    /**
     * The constants each clock is compared with from each location on, before it is reset (static guard analysis):
     * the tester's extrapolation bounds per state; null where only {@link #maxBounds} applies.
     */
    private final ClockLimits localBounds;
    private final Process[] processes;
    /** Per process and location, its outgoing edges in the order of the process's edge list. */
    private final Edge[][][] outgoing;
    /** Aligned with {@link #outgoing}: each edge's channel when it is fixed, -1 for none, -2 when computed. */
    private final int[][][] outgoingChannel;
    /** Aligned with {@link #outgoing}: each edge's guard (null for none), channel expression and updates. */
    private final Evaluator.Handle[][][] outgoingGuard;
    private final Evaluator.Handle[][][] outgoingChannelCode;
    private final Evaluator.Handle[][][][] outgoingUpdates;
    /** Per process and location: its invariant (null for none), whether it is committed, urgent or committed. */
    private final Evaluator.Handle[][] invariant;
    private final boolean[][] committed;
    private final boolean[][] urgentOrCommitted;
    /** Per channel: whether it is broadcast, urgent; whether any channel is urgent. */
    private final boolean[] broadcastChannel;
    private final boolean[] urgentChannel;
    private final boolean anyUrgentChannel;
    /** The clock assignments of the move being fired (cleared before its successor is handed on). */
    private final ClockResets resets = new ClockResets();
    /** The clock bounds of the invariants being applied, and the same as triples for {@link Dbm#constrainAll}. */
    private final ClockBounds bounds = new ClockBounds();
    private int[] listed = new int[24];

    /** A move: the edges that take part, in the order their updates run, and the channel (-1 for none). */
    public record Move(int channel, List<Step> steps) {
        public Move {
            steps = List.copyOf(steps);
        }
    }

    /** One process's edge in a move, with its select values in {@code frame}. */
    public record Step(int process, Edge edge, int[] frame) {
    }

    /** Receives the successors of a state. */
    public interface MoveSink {
        /** One successor, reached by {@code move}; {@code next} is owned by the sink. */
        void accept(Move move, SymState next);
    }

    /** The semantics of {@code network} with zones over {@code ticksPerUnit} ticks per model time unit. */
    public Semantics(Network network, int ticksPerUnit) {
        this(network, ticksPerUnit, true);
    }

    /**
     * The semantics of {@code network} with zones over {@code ticksPerUnit} ticks per model time unit, with or
     * without the tester's clock of time elapsed since its last observation (a model checker needs none).
     */
    public Semantics(Network network, int ticksPerUnit, boolean testerClock) {
        this.network = network;
        this.ticksPerUnit = ticksPerUnit;
        this.dimension = network.clockCount() + (testerClock ? 2 : 1);
        this.processes = network.processes().toArray(new Process[0]);
        checkSupported(network);
        this.evaluator = new Evaluator(network);
        this.maxBounds = testerClock ? maxBounds(network, ticksPerUnit, dimension) : null;
        this.localBounds = maxBounds == null ? null : ClockLimits.of(network, dimension, List.of());
        this.outgoing = new Edge[processes.length][][];
        this.outgoingChannel = new int[processes.length][][];
        this.outgoingGuard = new Evaluator.Handle[processes.length][][];
        this.outgoingChannelCode = new Evaluator.Handle[processes.length][][];
        this.outgoingUpdates = new Evaluator.Handle[processes.length][][][];
        this.invariant = new Evaluator.Handle[processes.length][];
        this.committed = new boolean[processes.length][];
        this.urgentOrCommitted = new boolean[processes.length][];
        for (Process p : processes) {
            int pi = p.index();
            int locations = p.locations().size();
            outgoing[pi] = new Edge[locations][];
            outgoingChannel[pi] = new int[locations][];
            outgoingGuard[pi] = new Evaluator.Handle[locations][];
            outgoingChannelCode[pi] = new Evaluator.Handle[locations][];
            outgoingUpdates[pi] = new Evaluator.Handle[locations][][];
            invariant[pi] = new Evaluator.Handle[locations];
            committed[pi] = new boolean[locations];
            urgentOrCommitted[pi] = new boolean[locations];
            for (int l = 0; l < locations; l++) {
                Location loc = p.locations().get(l);
                invariant[pi][l] = loc.invariant() == null ? null : evaluator.handle(loc.invariant());
                committed[pi][l] = loc.kind() == Location.Kind.COMMITTED;
                urgentOrCommitted[pi][l] = loc.isUrgentOrCommitted();
                int source = l;
                Edge[] from = p.edges().stream().filter(e -> e.source() == source).toArray(Edge[]::new);
                int[] channels = new int[from.length];
                Evaluator.Handle[] guards = new Evaluator.Handle[from.length];
                Evaluator.Handle[] channelCode = new Evaluator.Handle[from.length];
                Evaluator.Handle[][] updates = new Evaluator.Handle[from.length][];
                for (int i = 0; i < from.length; i++) {
                    Edge e = from[i];
                    channels[i] = e.sync() == null ? -1 : e.sync().channel() instanceof Expression.ChannelRef ref
                            && ref.type() instanceof Type.Channel ? ref.channel().index() : -2;
                    guards[i] = e.guard() == null ? null : evaluator.handle(e.guard());
                    channelCode[i] = channels[i] == -2 ? evaluator.handle(e.sync().channel()) : null;
                    updates[i] = e.updates().stream().map(evaluator::handle).toArray(Evaluator.Handle[]::new);
                }
                outgoing[pi][l] = from;
                outgoingChannel[pi][l] = channels;
                outgoingGuard[pi][l] = guards;
                outgoingChannelCode[pi][l] = channelCode;
                outgoingUpdates[pi][l] = updates;
            }
        }
        int channelCount = network.channelCount();
        this.broadcastChannel = new boolean[channelCount];
        this.urgentChannel = new boolean[channelCount];
        boolean anyUrgent = false;
        for (int c = 0; c < channelCount; c++) {
            Type.Channel kind = network.channelVariableOf(c).kind();
            broadcastChannel[c] = kind.broadcast();
            urgentChannel[c] = kind.urgent();
            anyUrgent |= kind.urgent();
        }
        this.anyUrgentChannel = anyUrgent;
    }

    /** The dimension of the zones: the model's clocks, the reference clock and the tester's clock if any. */
    public int dimension() {
        return dimension;
    }

    /** The network. */
    public Network network() {
        return network;
    }

    /** The evaluator of the network's expressions. */
    public Evaluator evaluator() {
        return evaluator;
    }

    /** Ticks per model time unit. */
    public int ticksPerUnit() {
        return ticksPerUnit;
    }

    /**
     * The number of the clock that measures time elapsed since the tester's last observation (the last clock of
     * a semantics made with the tester's clock).
     */
    public int elapsedClock() {
        return dimension - 1;
    }

    /** The initial state: every clock 0, initial locations and values, invariants applied. */
    public SymState initial() {
        int[] locations = new int[processes.length];
        for (Process p : processes) {
            locations[p.index()] = p.initial();
        }
        int[] vars = network.initialState();
        Dbm zone = Dbm.zero(dimension);
        if (!invariants(locations, vars, zone)) {
            throw new UnsupportedModelException("the initial state violates a location invariant");
        }
        return new SymState(locations, vars, zone);
    }

    /** Whether time may pass in {@code s}: no process is in an urgent or committed location, no urgent move. */
    public boolean mayDelay(SymState s) {
        int[] locations = s.locations;
        for (int p = 0; p < locations.length; p++) {
            int l = locations[p];
            if (l >= 0 && urgentOrCommitted[p][l]) {
                return false;
            }
        }
        return !urgentSyncEnabled(s);
    }

    /** Lets time pass in {@code s} (in place), as far as the invariants allow; false if nothing is left. */
    public boolean delay(SymState s) {
        if (mayDelay(s)) {
            s.zone.up();
        }
        return invariants(s.locations, s.vars, s.zone);
    }

    /**
     * Whether the processes {@code processes} accepts, on their own, let clock {@code clock} pass {@code ticks} in
     * {@code s}: none of them is in an urgent or committed location, no urgent synchronisation is enabled (whose
     * side is not told apart), and their invariants allow a valuation of {@code s} with the clock above {@code
     * ticks} after a delay. The other processes' invariants are not applied: they are what such a delay violates.
     */
    public boolean mayDelayPast(SymState s, java.util.function.IntPredicate processes, int clock, long ticks) {
        int[] locations = s.locations;
        for (int p = 0; p < locations.length; p++) {
            int l = locations[p];
            if (processes.test(p) && l >= 0 && urgentOrCommitted[p][l]) {
                return false;
            }
        }
        if (urgentSyncEnabled(s)) {
            return false;
        }
        Dbm zone = s.zone.copy();
        zone.up();
        for (int p = 0; p < locations.length; p++) {
            int l = locations[p];
            Evaluator.Handle inv = l < 0 || !processes.test(p) ? null : invariant[p][l];
            if (inv != null && !evaluator.constrain(inv, s.vars, null, zone, ticksPerUnit)) {
                return false;
            }
        }
        return zone.constrain(0, clock, Bound.lt((int) -Math.min(ticks, Bound.MAX_VALUE)));
    }

    /** Applies the invariants of {@code locations} to {@code zone}; false if the zone becomes empty. */
    public boolean invariants(int[] locations, int[] vars, Dbm zone) {
        // their clock bounds listed first and added together (Dbm.constrainAll); when listing meets a model
        // error, one invariant at a time, so that an error is raised exactly when it was before
        bounds.clear();
        try {
            for (int p = 0; p < locations.length; p++) {
                int l = locations[p];
                Evaluator.Handle inv = l < 0 ? null : invariant[p][l];
                if (inv != null && !evaluator.clockBounds(inv, vars, null, ticksPerUnit, bounds)) {
                    // a data conjunct is false: the zone as applying them one at a time leaves it
                    applyListed(zone);
                    return false;
                }
            }
        } catch (ModelRuntimeException e) {
            return invariantsOneByOne(locations, vars, zone);
        }
        return applyListed(zone) && !zone.isEmpty();
    }

    /** Adds the bounds listed in {@link #bounds} to {@code zone}; false if it becomes empty. */
    private boolean applyListed(Dbm zone) {
        int n = bounds.size();
        if (listed.length < 3 * n) {
            listed = new int[3 * n];
        }
        for (int k = 0; k < n; k++) {
            listed[3 * k] = bounds.i(k);
            listed[3 * k + 1] = bounds.j(k);
            listed[3 * k + 2] = bounds.bound(k);
        }
        return zone.constrainAll(listed, 3 * n);
    }

    private boolean invariantsOneByOne(int[] locations, int[] vars, Dbm zone) {
        for (int p = 0; p < locations.length; p++) {
            int l = locations[p];
            if (l < 0) {
                continue;
            }
            Evaluator.Handle inv = invariant[p][l];
            if (inv != null && !evaluator.constrain(inv, vars, null, zone, ticksPerUnit)) {
                return false;
            }
        }
        return !zone.isEmpty();
    }

    /** The invariant of location {@code l} of process {@code p} (null for none; {@code l} may be -1). */
    Evaluator.Handle invariantOf(int p, int l) {
        return l < 0 ? null : invariant[p][l];
    }

    /**
     * Extrapolates a state's zone in place, the elapsed clock kept exact: Extra+_M with the bounds of the state's
     * locations (a clock that no process compares with a constant before it resets it is free: its value can no
     * longer matter), else Extra_M over the model's largest constants. Both keep the zone within its closure by
     * regions of those bounds, whose valuations have the same future.
     */
    public void extrapolate(SymState s) {
        extrapolate(s, extrapolationBounds(s.locations));
    }

    /**
     * The bounds {@link #extrapolate(SymState)} uses for a state in {@code locations} (they depend on the
     * locations alone), for {@link #extrapolate(SymState, int[])}; null when only the model's largest constants
     * apply.
     */
    int[] extrapolationBounds(int[] locations) {
        if (localBounds == null) {
            return null;
        }
        int[] lower = new int[dimension];
        int[] bounds = new int[dimension];
        localBounds.fill(locations, lower, bounds);
        for (int x = 1; x < dimension - 1; x++) {
            int m = Math.max(lower[x], bounds[x]);
            // at most the model's largest constant, which maxBounds has checked fits in ticks
            bounds[x] = m < 0 ? -1 : (int) Math.min((long) m * ticksPerUnit, maxBounds[x]);
        }
        bounds[dimension - 1] = maxBounds[dimension - 1];
        return bounds;
    }

    /** {@link #extrapolate(SymState)} with the bounds {@link #extrapolationBounds} gave for its locations. */
    void extrapolate(SymState s, int[] bounds) {
        if (bounds != null) {
            s.zone.extrapolateLU(bounds, bounds);
        } else if (maxBounds != null) {
            s.zone.extrapolateMaxBounds(maxBounds);
        }
    }

    // ================================================================ discrete moves

    /** The frame of an edge without selects (never changed: the evaluator copies frames). */
    private static final int[] NO_FRAME = new int[0];

    /** A process's edge that may take part in a move, its data guard true. */
    record Candidate(int process, Edge edge, int[] frame, int channel, Evaluator.Handle guard,
                     Evaluator.Handle[] updates) {
    }

    /** Receives the moves of a state as the edges that take part (in the order their updates run). */
    interface MoveEnumerator {
        void move(List<Candidate> participants, int channel);
    }

    /** Every discrete successor of {@code s}, without delay. */
    public void moves(SymState s, MoveSink sink) {
        moves(s, c -> true, sink);
    }

    /**
     * The discrete successors of {@code s} by moves whose channel (-1 for an edge without synchronisation)
     * {@code channels} accepts; moves on other channels are not computed at all.
     */
    public void moves(SymState s, java.util.function.IntPredicate channels, MoveSink sink) {
        enumerate(s, channels, (participants, channel) -> fire(s, participants, channel, sink));
    }

    /**
     * The moves of {@code s} on the channels {@code channels} accepts, in the order {@link #moves} fires them,
     * without firing them; they depend on the discrete part of {@code s} alone.
     */
    void enumerate(SymState s, java.util.function.IntPredicate channels, MoveEnumerator out) {
        List<Candidate> candidates = candidates(s);
        boolean committed = inCommitted(s);
        for (Candidate c : candidates) {
            Edge.Sync sync = c.edge.sync();
            if (sync == null) {
                if ((!committed || isCommitted(s, c.process)) && channels.test(-1)) {
                    out.move(List.of(c), -1);
                }
                continue;
            }
            if (sync.direction() != Edge.Direction.SEND || !channels.test(c.channel)) {
                continue;
            }
            if (broadcastChannel[c.channel]) {
                broadcast(s, c, candidates, committed, out);
            } else {
                for (Candidate r : candidates) {
                    if (r.process != c.process && r.channel == c.channel && r.edge.sync() != null
                            && r.edge.sync().direction() == Edge.Direction.RECEIVE
                            && (!committed || isCommitted(s, c.process) || isCommitted(s, r.process))) {
                        out.move(List.of(c, r), c.channel);
                    }
                }
            }
        }
    }

    private void broadcast(SymState s, Candidate sender, List<Candidate> candidates, boolean committed,
                           MoveEnumerator out) {
        List<List<Candidate>> perProcess = new ArrayList<>();
        for (Process p : processes) {
            if (p.index() == sender.process) {
                continue;
            }
            List<Candidate> receivers = new ArrayList<>();
            for (Candidate r : candidates) {
                if (r.process == p.index() && r.channel == sender.channel && r.edge.sync() != null
                        && r.edge.sync().direction() == Edge.Direction.RECEIVE) {
                    receivers.add(r);
                }
            }
            if (!receivers.isEmpty()) {
                perProcess.add(receivers);
            }
        }
        int[] choice = new int[perProcess.size()];
        while (true) {
            List<Candidate> participants = new ArrayList<>();
            participants.add(sender);
            boolean anyCommitted = isCommitted(s, sender.process);
            for (int i = 0; i < choice.length; i++) {
                Candidate r = perProcess.get(i).get(choice[i]);
                participants.add(r);
                anyCommitted |= isCommitted(s, r.process);
            }
            if (!committed || anyCommitted) {
                out.move(participants, sender.channel);
            }
            int k = choice.length - 1;
            while (k >= 0 && choice[k] == perProcess.get(k).size() - 1) {
                choice[k] = 0;
                k--;
            }
            if (k < 0) {
                return;
            }
            choice[k]++;
        }
    }

    void fire(SymState s, List<Candidate> participants, int channel, MoveSink sink) {
        Dbm zone = s.zone.copy();
        for (Candidate c : participants) {
            if (c.guard != null && !evaluator.constrain(c.guard, s.vars, c.frame, zone, ticksPerUnit)) {
                return;
            }
        }
        if (zone.isEmpty()) {
            return;
        }
        int[] vars = s.vars.clone();
        resets.clear();
        try {
            for (Candidate c : participants) {
                for (Evaluator.Handle update : c.updates) {
                    evaluator.execute(update, vars, c.frame, resets);
                }
            }
            resets.applyTo(zone, ticksPerUnit);
        } finally {
            resets.clear();
        }
        int[] locations = s.locations.clone();
        Step[] steps = new Step[participants.size()];
        for (int i = 0; i < steps.length; i++) {
            Candidate c = participants.get(i);
            locations[c.process] = c.edge.target();
            steps[i] = new Step(c.process, c.edge, c.frame);
        }
        if (!invariants(locations, vars, zone)) {
            return;
        }
        sink.accept(new Move(channel, List.of(steps)), new SymState(locations, vars, zone));
    }

    /**
     * The moves of {@code s} in which the processes {@code inside} accepts synchronise on {@code channel} with a
     * partner outside them (the other side of an observable channel): when {@code send}, each of their enabled
     * sending edges alone (a move must involve a committed process when one of them is in a committed location);
     * else each enabled receiving edge alone, or for a broadcast channel one receiving edge of every process that
     * has one. The outside partner's updates are not run: a caller that receives sets the attached variables in
     * {@code s} first.
     */
    public void openMoves(SymState s, java.util.function.IntPredicate inside, int channel, boolean send,
                          MoveSink sink) {
        Edge.Direction direction = send ? Edge.Direction.SEND : Edge.Direction.RECEIVE;
        List<Candidate> own = new ArrayList<>();
        for (Candidate c : candidates(s)) {
            if (c.channel == channel && inside.test(c.process) && c.edge.sync() != null
                    && c.edge.sync().direction() == direction) {
                own.add(c);
            }
        }
        if (send) {
            boolean committedNow = inCommitted(s);
            for (Candidate c : own) {
                if (!committedNow || isCommitted(s, c.process)) {
                    fire(s, List.of(c), channel, sink);
                }
            }
            return;
        }
        if (!broadcastChannel[channel]) {
            for (Candidate c : own) {
                fire(s, List.of(c), channel, sink);
            }
            return;
        }
        List<List<Candidate>> perProcess = new ArrayList<>();
        for (Process p : processes) {
            List<Candidate> mine = own.stream().filter(c -> c.process == p.index()).toList();
            if (!mine.isEmpty()) {
                perProcess.add(mine);
            }
        }
        if (perProcess.isEmpty()) {
            return;
        }
        int[] choice = new int[perProcess.size()];
        while (true) {
            List<Candidate> participants = new ArrayList<>();
            for (int i = 0; i < choice.length; i++) {
                participants.add(perProcess.get(i).get(choice[i]));
            }
            fire(s, participants, channel, sink);
            int k = choice.length - 1;
            while (k >= 0 && choice[k] == perProcess.get(k).size() - 1) {
                choice[k] = 0;
                k--;
            }
            if (k < 0) {
                return;
            }
            choice[k]++;
        }
    }

    /** Whether {@code channel} is urgent. */
    public boolean isUrgent(int channel) {
        return urgentChannel[channel];
    }

    /** The edges whose data guards hold in {@code s}, once per select binding. */
    private List<Candidate> candidates(SymState s) {
        List<Candidate> out = new ArrayList<>();
        for (int p = 0; p < processes.length; p++) {
            int l = s.locations[p];
            if (l < 0) {
                continue;
            }
            Edge[] edges = outgoing[p][l];
            int[] channels = outgoingChannel[p][l];
            Evaluator.Handle[] guards = outgoingGuard[p][l];
            Evaluator.Handle[] channelCode = outgoingChannelCode[p][l];
            Evaluator.Handle[][] updates = outgoingUpdates[p][l];
            for (int i = 0; i < edges.length; i++) {
                Edge e = edges[i];
                List<Edge.Select> selects = e.selects();
                int fixed = channels[i];
                Evaluator.Handle guard = guards[i];
                if (selects.isEmpty()) {
                    int[] frame = e.frameSize() == 0 ? NO_FRAME : new int[e.frameSize()];
                    if (guard == null || evaluator.dataHolds(guard, s.vars, frame)) {
                        int channel = fixed != -2 ? fixed : evaluator.channel(channelCode[i], s.vars, frame);
                        out.add(new Candidate(p, e, frame, channel, guard, updates[i]));
                    }
                    continue;
                }
                int[] frame = new int[e.frameSize()];
                for (Edge.Select sel : selects) {
                    frame[sel.slot()] = sel.lower();
                }
                while (true) {
                    if (guard == null || evaluator.dataHolds(guard, s.vars, frame)) {
                        int channel = fixed != -2 ? fixed : evaluator.channel(channelCode[i], s.vars, frame);
                        out.add(new Candidate(p, e, frame.clone(), channel, guard, updates[i]));
                    }
                    int k = selects.size() - 1;
                    while (k >= 0 && frame[selects.get(k).slot()] == selects.get(k).upper()) {
                        frame[selects.get(k).slot()] = selects.get(k).lower();
                        k--;
                    }
                    if (k < 0) {
                        break;
                    }
                    frame[selects.get(k).slot()]++;
                }
            }
        }
        return out;
    }

    private boolean urgentSyncEnabled(SymState s) {
        if (!anyUrgentChannel) {
            return false;
        }
        List<Candidate> candidates = candidates(s);
        for (Candidate send : candidates) {
            if (send.edge.sync() == null || send.edge.sync().direction() != Edge.Direction.SEND
                    || !urgentChannel[send.channel]) {
                continue;
            }
            if (broadcastChannel[send.channel]) {
                return true;
            }
            for (Candidate r : candidates) {
                if (r.process != send.process && r.channel == send.channel && r.edge.sync() != null
                        && r.edge.sync().direction() == Edge.Direction.RECEIVE) {
                    return true;
                }
            }
        }
        return false;
    }

    private boolean inCommitted(SymState s) {
        for (int p = 0; p < processes.length; p++) {
            if (isCommitted(s, p)) {
                return true;
            }
        }
        return false;
    }

    private boolean isCommitted(SymState s, int p) {
        int l = s.locations[p];
        return l >= 0 && committed[p][l];
    }

    // ================================================================ checks and constants

    private static void checkSupported(Network network) {
        if (!network.startErrors().isEmpty()) {
            throw new UnsupportedModelException("the model cannot start: " + network.startErrors().get(0).format());
        }
        if (network.channelPriority().stream().anyMatch(p -> p != 0)
                || network.processes().stream().anyMatch(p -> p.priority() != 0)) {
            throw new UnsupportedModelException("channel and process priorities are not supported by DTRON's engine"
                    + " yet");
        }
        for (Process p : network.processes()) {
            for (Location l : p.locations()) {
                if (l.invariant() != null && containsRate(l.invariant())) {
                    throw new UnsupportedModelException(l.pos().fragment().file() + ":" + l.pos().line() + ": clock"
                            + " rates (stopwatches) in the invariant of " + p.name() + "." + l.name()
                            + " are not supported by DTRON's engine");
                }
            }
            for (Edge e : p.edges()) {
                if (e.sync() == null) {
                    continue;
                }
                if (e.sync().direction() == Edge.Direction.CSP) {
                    throw new UnsupportedModelException(e.pos().fragment().file() + ":" + e.pos().line()
                            + ": CSP synchronisation (sync without ! or ?) in " + p.name()
                            + " is not supported by DTRON's engine");
                }
                if (e.sync().direction() == Edge.Direction.RECEIVE && e.guard() != null
                        && e.guard().type() instanceof Type.ClockConstraint
                        && e.sync().channel().type() instanceof Type.Channel c && c.broadcast()) {
                    throw new UnsupportedModelException(e.pos().fragment().file() + ":" + e.pos().line()
                            + ": a clock guard on a broadcast receiver (in " + p.name()
                            + ") is not supported by DTRON's engine");
                }
            }
        }
    }

    private static boolean containsRate(Expression e) {
        if (e instanceof Expression.ClockRate) {
            return true;
        }
        return e instanceof Expression.Binary b && (containsRate(b.left()) || containsRate(b.right()));
    }

    /**
     * The largest constant each clock is compared with, in ticks; null (no extrapolation) when a clock is
     * compared with a non-constant expression or the model has clock differences.
     */
    private static int[] maxBounds(Network network, int ticksPerUnit, int dimension) {
        long[] max = new long[dimension];
        List<Expression> constraints = new ArrayList<>();
        for (Process p : network.processes()) {
            for (Location l : p.locations()) {
                if (l.invariant() != null) {
                    constraints.add(l.invariant());
                }
            }
            for (Edge e : p.edges()) {
                if (e.guard() != null) {
                    constraints.add(e.guard());
                }
            }
        }
        for (Expression c : constraints) {
            if (!collect(c, max)) {
                return null;
            }
        }
        int[] out = new int[dimension];
        for (int i = 1; i < dimension - 1; i++) {
            long ticks = max[i] * ticksPerUnit;
            if (ticks > Bound.MAX_VALUE / 4) {
                return null;
            }
            out[i] = (int) ticks;
        }
        out[dimension - 1] = Bound.MAX_VALUE / 2;
        return out;
    }

    /** Adds the atoms' constants to the clocks they bound; false when an atom defeats extrapolation. */
    private static boolean collect(Expression e, long[] max) {
        if (!(e.type() instanceof Type.ClockConstraint) || !(e instanceof Expression.Binary b)) {
            return true;
        }
        if (b.op() == Expression.Operator.AND || b.op() == Expression.Operator.OR) {
            return collect(b.left(), max) && collect(b.right(), max);
        }
        if (b.left().type() instanceof Type.ClockDifference || b.right().type() instanceof Type.ClockDifference
                || b.left().type() instanceof Type.Clock && b.right().type() instanceof Type.Clock) {
            return false;
        }
        long[] constant = {0};
        List<Integer> clocks = new ArrayList<>();
        if (!ClockLimits.walk(b.left(), constant, clocks) || !ClockLimits.walk(b.right(), constant, clocks)) {
            return false;
        }
        for (int i : clocks) {
            max[i] = Math.max(max[i], constant[0]);
        }
        return true;
    }

    /**
     * An edge of a process accepted by {@code processes} that could send on {@code channel} in {@code s} (its
     * guard satisfiable in the zone), whoever receives; null if there is none.
     */
    public Step enabledSend(SymState s, int channel, java.util.function.IntPredicate processes) {
        for (Candidate c : candidates(s)) {
            if (c.channel != channel || !processes.test(c.process) || c.edge.sync() == null
                    || c.edge.sync().direction() != Edge.Direction.SEND) {
                continue;
            }
            Dbm zone = s.zone.copy();
            if (c.guard == null || evaluator.constrain(c.guard, s.vars, c.frame, zone, ticksPerUnit)) {
                return new Step(c.process, c.edge, c.frame);
            }
        }
        return null;
    }

    /** The names of a state's locations, for explanations: {@code Lamp.off, User.idle}. */
    public String describe(SymState s, boolean[] include) {
        StringBuilder sb = new StringBuilder();
        for (Process p : processes) {
            int l = s.locations[p.index()];
            if (l < 0 || include != null && !include[p.index()]) {
                continue;
            }
            sb.append(sb.length() == 0 ? "" : ", ").append(p.name()).append('.').append(p.locations().get(l).name());
        }
        return sb.toString();
    }

    /** An edge as people read it: {@code Lamp: off -> on}. */
    public String describe(Step step) {
        Process p = processes[step.process()];
        String select = step.edge().selects().isEmpty() ? "" : " " + Arrays.toString(step.frame());
        return p.name() + ": " + p.locations().get(step.edge().source()).name() + " -> "
                + p.locations().get(step.edge().target()).name() + select;
    }
}
