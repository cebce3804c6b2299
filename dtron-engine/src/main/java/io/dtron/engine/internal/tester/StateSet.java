package io.dtron.engine.internal.tester;

import io.dtron.engine.internal.sem.DiscreteCache;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Collections;
import java.util.Deque;
import java.util.List;

/**
 * The tester's knowledge: the symbolic states the closed network may be in, the elapsed clock counting from the
 * set's time (its reference): 0 in every zone at the time of the last observation when that time is on a tick and
 * known exactly, else within the observation's window ({@link #within}). Immutable; every operation gives a new
 * set.
 */
public final class StateSet {
    /** The most states a closure may visit before the model is declared too nondeterministic to follow. */
    static final int MAX_STATES = 200_000;

    private final Semantics semantics;
    private final Partition partition;
    private final Caches caches;
    private final List<SymState> states;

    /**
     * What the sets made from one initial set learn about discrete parts (see {@link DiscreteCache}), for
     * internal and for observable moves, kept from step to step as a run comes back to the same locations and
     * values; each starts again when it holds {@link #LIMIT} discrete parts. Not thread-safe, as the semantics
     * they share is not.
     */
    static final class Caches {
        static final int LIMIT = 2_000;
        final DiscreteCache internal;
        final DiscreteCache observable;

        Caches(Semantics semantics, Partition partition) {
            this.internal = new DiscreteCache(semantics, c -> c < 0 || partition.observable(c) == Partition.INTERNAL,
                    LIMIT);
            this.observable = new DiscreteCache(semantics,
                    c -> c >= 0 && partition.observable(c) != Partition.INTERNAL, LIMIT);
        }
    }

    /** A successor of the set by one move, with the move. */
    public record Successor(Semantics.Move move, SymState from, SymState state) {
    }

    private StateSet(Semantics semantics, Partition partition, Caches caches, List<SymState> states) {
        this.semantics = semantics;
        this.partition = partition;
        this.caches = caches;
        this.states = Collections.unmodifiableList(states);
    }

    /** The set holding the initial state. */
    public static StateSet initial(Semantics semantics, Partition partition) {
        return new StateSet(semantics, partition, new Caches(semantics, partition), List.of(semantics.initial()));
    }

    /** The states (zones not to be changed). */
    public List<SymState> states() {
        return states;
    }

    /** The cache of the moves on observable channels, for plans. */
    DiscreteCache observableMoves() {
        return caches.observable;
    }

    /** Whether no state is left. */
    public boolean isEmpty() {
        return states.isEmpty();
    }

    /**
     * Every state reachable from this set by delays and internal moves while the elapsed clock stays within
     * {@code [0, horizonTicks]}; zones keep the elapsed clock, so they tell when each state is possible.
     */
    public List<SymState> reach(long horizonTicks) {
        return reach(horizonTicks, null);
    }

    /** {@link #reach(long)}, telling {@code internalMoves} (when not null) every move it follows. */
    private List<SymState> reach(long horizonTicks, java.util.function.Consumer<Semantics.Move> internalMoves) {
        int elapsed = semantics.elapsedClock();
        int horizon = (int) Math.min(horizonTicks, Bound.MAX_VALUE);
        Passed passed = new Passed();
        DiscreteCache cache = caches.internal;
        Deque<SymState> waiting = new ArrayDeque<>();
        for (SymState s : states) {
            waiting.add(copy(s));
        }
        int visited = 0;
        Semantics.MoveSink sink = internalMoves == null ? (move, next) -> waiting.add(next) : (move, next) -> {
            internalMoves.accept(move);
            waiting.add(next);
        };
        while (!waiting.isEmpty()) {
            SymState s = waiting.poll();
            if (!cache.delay(s, elapsed, Bound.le(horizon))) {
                continue;
            }
            if (!passed.add(s)) {
                continue;
            }
            if (++visited > MAX_STATES) {
                throw new IllegalStateException("more than " + MAX_STATES + " symbolic states within one step:"
                        + " the model is too nondeterministic to follow online");
            }
            cache.moves(s, sink);
        }
        return passed.states();
    }

    /** The set after exactly {@code deltaTicks} without observation (empty if time cannot pass that far). */
    public StateSet after(long deltaTicks) {
        return afterWindow(deltaTicks, deltaTicks, false, null);
    }

    /**
     * The set after a delay somewhere in {@code [fromTicks, toTicks]} (an observation's window: its time rounded
     * to ticks, give or take its clock error), its time the window's start: the elapsed clock is moved back by
     * {@code fromTicks}, not set to 0, so that the zones keep when in the window each state's event came. Tells
     * {@code internalMoves} (when not null) every internal move the closure follows within the window: the moves
     * some state may have taken (for coverage).
     */
    public StateSet within(long fromTicks, long toTicks, java.util.function.Consumer<Semantics.Move> internalMoves) {
        return afterWindow(fromTicks, toTicks, true, internalMoves);
    }

    private StateSet afterWindow(long fromTicks, long toTicks, boolean keepWhen,
                                 java.util.function.Consumer<Semantics.Move> internalMoves) {
        int elapsed = semantics.elapsedClock();
        int start = (int) Math.min(fromTicks, Bound.MAX_VALUE);
        Passed out = new Passed();
        // the states of reach are its own copies: changed in place
        for (SymState t : reach(toTicks, internalMoves)) {
            Dbm z = t.zone();
            if (!z.constrain(0, elapsed, Bound.le(-start))) {
                continue;
            }
            if (keepWhen) {
                z.shift(elapsed, start);
            } else {
                z.reset(elapsed, 0);
            }
            semantics.extrapolate(t);
            out.add(t);
        }
        return new StateSet(semantics, partition, caches, out.states());
    }

    /** The successors of this set by the moves on channel number {@code channel} (no delay before them). */
    public List<Successor> successors(int channel) {
        List<Successor> out = new ArrayList<>();
        boolean observable = channel >= 0 && partition.observable(channel) != Partition.INTERNAL;
        DiscreteCache cache = observable ? caches.observable : new DiscreteCache(semantics, c -> c == channel, Caches.LIMIT);
        for (SymState s : states) {
            cache.moves(s, channel, (move, next) -> out.add(new Successor(move, s, next)));
        }
        return out;
    }

    /** A set of states (deduplicated by inclusion). */
    public StateSet of(List<SymState> next) {
        Passed out = new Passed();
        for (SymState s : next) {
            out.add(s);
        }
        return new StateSet(semantics, partition, caches, out.states());
    }

    private static SymState copy(SymState s) {
        return s.copy();
    }

    /**
     * States grouped by their discrete part (locations and variables), so that a new state is compared by zone
     * inclusion only with the states of its own group.
     */
    private static final class Passed {
        private final java.util.Map<Integer, List<SymState>> groups = new java.util.HashMap<>();
        private final List<SymState> order = new ArrayList<>();

        /** Adds {@code s} unless a state of its group covers it; drops the states it covers. */
        boolean add(SymState s) {
            List<SymState> group = groups.computeIfAbsent(s.discreteHash(), k -> new ArrayList<>(2));
            for (SymState o : group) {
                if (o.sameDiscrete(s) && s.zone().isSubsetOf(o.zone())) {
                    return false;
                }
            }
            int before = group.size();
            group.removeIf(o -> o.sameDiscrete(s) && o.zone().isSubsetOf(s.zone()));
            if (group.size() != before) {
                order.removeIf(o -> o.sameDiscrete(s) && o.zone().isSubsetOf(s.zone()));
            }
            group.add(s);
            order.add(s);
            return true;
        }

        List<SymState> states() {
            return order;
        }
    }
}
