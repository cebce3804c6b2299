package io.dtron.engine.internal.monitor;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.sem.DiscreteCache;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.engine.internal.zone.Relation;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Collections;
import java.util.Deque;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.function.IntPredicate;
import java.util.function.Predicate;

/**
 * The monitor's knowledge of a closed network: sets of symbolic states whose elapsed clock counts from the start of the
 * last event's window (they keep when in it the event came), every channel of the interface observable and the others
 * internal. Sets are interned as {@link Node}s, and a node remembers where each event (channel, values, delay in ticks)
 * took it, so that a run that comes back to the same states and delays costs a hash lookup per event. Not thread-safe.
 */
public final class Tracker {
    /**
     * The most states the exploration of the reachable states may visit, and the most a closure may visit beyond
     * the states it starts from (a monitor that starts from every reachable state starts with up to as many).
     */
    public static final int MAX_STATES = 200_000;
    /** How long the exploration of the reachable states may take: 10 s. */
    static final long REACHABLE_NANOS = 10_000_000_000L;
    /** How many nodes are interned before the table and the transitions remembered start again. */
    static final int NODE_LIMIT = 4_096;
    /** How many transitions one node remembers before it forgets them all. */
    static final int TRANSITION_LIMIT = 4_096;
    /** How many transitions all nodes remember before the tracker forgets all nodes and transitions. */
    static final int REMEMBERED_LIMIT = 32_768;
    /**
     * How many discrete parts the cache of moves holds before it forgets them all: a cache that forgets every few
     * hundred events enumerates the moves anew (2,000 made the replay of LightContr in {@code MonitorBench} about a
     * third slower), and one that keeps too many makes each garbage collection copy them (50,000 cost the street
     * lights' replay 5 us an event in collections).
     */
    static final int CACHED = 10_000;

    private final Semantics semantics;
    private final int elapsed;
    /** The moves of every channel, internal and observable: one enumeration per discrete part for both. */
    private final DiscreteCache all;
    /** Whether a channel (-1 none) is internal. */
    private final IntPredicate internal;
    private final Map<NodeKey, Node> nodes = new HashMap<>();
    private final TransitionKey probe = new TransitionKey();
    /** Whether transitions are remembered (off only to compare with: the sets are the same either way). */
    private final boolean remember;
    /** Transitions remembered since the tracker last forgot. */
    private int remembered;
    /** How many steps were answered from a remembered transition. */
    private long recalled;
    /** No channel, for {@link #delayed}. */
    private static final int NO_CHANNEL = Integer.MIN_VALUE;
    /** The empty set: where an event that no state allows leads. */
    public final Node empty = new Node(List.of());

    /** A tracker of {@code semantics} (made with the tester's clock) in which the channels of {@code observed} are seen. */
    public Tracker(Semantics semantics, boolean[] observed) {
        this(semantics, observed, true);
    }

    /**
     * A tracker that remembers no transition when {@code remember} is false: every step is computed, as a check
     * that remembering changes nothing.
     */
    public Tracker(Semantics semantics, boolean[] observed, boolean remember) {
        this.remember = remember;
        this.semantics = semantics;
        this.elapsed = semantics.elapsedClock();
        this.all = new DiscreteCache(semantics, c -> true, CACHED);
        this.internal = c -> c < 0 || !observed[c];
    }

    /** How many steps were answered from a remembered transition so far. */
    public long recalled() {
        return recalled;
    }

    /** The semantics. */
    public Semantics semantics() {
        return semantics;
    }

    /**
     * A set of states at one time, interned: equal sets are one node. Its states are not to be changed. It
     * remembers the transitions taken from it and the delays it has been found to allow.
     */
    public static final class Node {
        private final List<SymState> states;
        /** The transitions taken from it; null until the first. */
        private Map<TransitionKey, Node> next;
        /** The most elapsed ticks known to be allowed (-1: none known). */
        long allowedUntil = -1;
        /** The raw bound on elapsed ticks beyond which no state is left, once found; {@link Bound#INFINITY} if none. */
        int deadline = Integer.MIN_VALUE;

        Node(List<SymState> states) {
            this.states = Collections.unmodifiableList(states);
        }

        /** The states (zones not to be changed). */
        public List<SymState> states() {
            return states;
        }

        /** Whether no state is left. */
        public boolean isEmpty() {
            return states.isEmpty();
        }
    }

    /** The node of the set holding {@code states} (deduplicated by inclusion first). */
    public Node node(List<SymState> states) {
        Passed passed = new Passed();
        for (SymState s : states) {
            passed.add(s);
        }
        return intern(passed.states());
    }

    private Node intern(List<SymState> states) {
        if (states.isEmpty()) {
            return empty;
        }
        NodeKey key = new NodeKey(states);
        Node n = nodes.get(key);
        if (n == null) {
            if (nodes.size() >= NODE_LIMIT) {
                forget();
            }
            n = new Node(states);
            nodes.put(key, n);
        }
        return n;
    }

    /**
     * The node after the event on channel {@code channel} whose attached variables (state slots {@code slots})
     * carry {@code values}, some time in {@code [fromTicks, toTicks]} after {@code from}'s time; {@link #empty}
     * when no state allows it then.
     */
    public Node step(Node from, int channel, int[] slots, int[] values, long fromTicks, long toTicks,
            boolean keepWhen) {
        TransitionKey k = probe.set(channel, values, fromTicks, toTicks, keepWhen);
        Node cached = remember && from.next != null ? from.next.get(k) : null;
        if (cached != null) {
            recalled++;
            return cached;
        }
        List<SymState> out = new ArrayList<>();
        for (SymState s : delayed(from, fromTicks, toTicks, keepWhen, channel, slots, values)) {
            all.moves(s, channel, (move, next) -> {
                if (matches(next, slots, values)) {
                    out.add(next);
                }
            });
        }
        Node result = node(out);
        if (!remember) {
            return result;
        }
        if (++remembered > REMEMBERED_LIMIT) {
            forget();
        }
        if (from.next == null) {
            from.next = new HashMap<>();
        } else if (from.next.size() >= TRANSITION_LIMIT) {
            from.next.clear();
        }
        from.next.put(k.copy(), result);
        return result;
    }

    /**
     * Forgets the interned nodes and their transitions: a run that keeps meeting new sets (clocks that are not
     * reset, delays that do not repeat) would otherwise keep every set it met, each reachable from the one before
     * it. A node made before is still right; it is only no longer shared.
     */
    private void forget() {
        for (Node n : nodes.values()) {
            n.next = null;
        }
        nodes.clear();
        remembered = 0;
    }

    private static boolean matches(SymState s, int[] slots, int[] values) {
        for (int i = 0; i < slots.length; i++) {
            if (s.var(slots[i]) != values[i]) {
                return false;
            }
        }
        return true;
    }

    /** The successors of {@code at}'s states by the moves on {@code channel}, with any values. */
    public List<Semantics.Move> moves(Node at, int channel, List<SymState> targets) {
        List<Semantics.Move> moves = new ArrayList<>();
        for (SymState s : at.states) {
            all.moves(s, channel, (move, next) -> {
                moves.add(move);
                targets.add(next);
            });
        }
        return moves;
    }

    /** The successors of {@code s} by the moves on observable channel {@code channel}. */
    public void observableMoves(SymState s, int channel, Semantics.MoveSink sink) {
        all.moves(s, channel, sink);
    }

    /**
     * The set after a delay somewhere in {@code [fromTicks, toTicks]} without an event, with the elapsed clock set
     * back to 0; {@link #empty} if time cannot pass that far.
     */
    public Node afterWindow(Node from, long fromTicks, long toTicks, boolean keepWhen) {
        return intern(delayed(from, fromTicks, toTicks, keepWhen, NO_CHANNEL, null, null));
    }

    /**
     * {@link #afterWindow}'s states, not interned (the step of an event needs no node of them); with a channel
     * ({@link #NO_CHANNEL} for none), only those whose discrete part has a move on it whose data guard holds and
     * whose successor's variables at {@code slots} hold {@code values}: the others have no successor the step
     * keeps, and a state is compared only with those of its discrete part, so the states kept are those the step
     * would keep from all, in the same order.
     */
    private List<SymState> delayed(Node from, long fromTicks, long toTicks, boolean keepWhen, int channel,
            int[] slots, int[] values) {
        Passed out = new Passed();
        for (SymState t : reach(from, toTicks)) {
            if (channel != NO_CHANNEL && !all.mayMove(t, channel, slots, values)) {
                continue;
            }
            Dbm z = t.zone();
            int start = (int) Math.min(fromTicks, Bound.MAX_VALUE);
            if (!z.constrain(0, elapsed, Bound.le(-start))) {
                continue;
            }
            if (keepWhen) {
                z.shift(elapsed, start); // the set's time is the window's start: when in it the event came is kept
            } else {
                z.reset(elapsed, 0);
            }
            all.extrapolate(t);
            out.add(t);
        }
        return out.states();
    }

    /**
     * Every state reachable from {@code from} by delays and internal moves while the elapsed clock stays within
     * {@code [0, horizonTicks]}; copies, whose zones keep the elapsed clock.
     */
    public List<SymState> reach(Node from, long horizonTicks) {
        int horizon = (int) Math.min(horizonTicks, Bound.MAX_VALUE);
        Passed passed = new Passed();
        Deque<SymState> waiting = new ArrayDeque<>();
        for (SymState s : from.states) {
            waiting.add(s.copy());
        }
        int visited = 0;
        int most = from.states.size() + MAX_STATES;
        Semantics.MoveSink sink = (move, next) -> waiting.add(next);
        while (!waiting.isEmpty()) {
            SymState s = waiting.poll();
            if (!all.delay(s, elapsed, Bound.le(horizon)) || !passed.add(s)) {
                continue;
            }
            if (++visited > most) {
                throw new UnsupportedModelException("more than " + most + " symbolic states between two events"
                        + " (from " + from.states.size() + "): the model is too nondeterministic to follow");
            }
            all.moves(s, internal, sink);
        }
        return passed.states();
    }

    /**
     * Whether time may pass {@code ticks} after {@code n}'s time without an event; the answer is remembered, and a
     * closure asked for is made at least twice as long as the last, so that a clock ticking toward a far deadline
     * costs few closures.
     */
    public boolean allows(Node n, long ticks) {
        if (ticks <= n.allowedUntil) {
            return true;
        }
        if (n.deadline != Integer.MIN_VALUE) {
            return n.deadline == Bound.INFINITY || Bound.compare(Bound.le((int) Math.min(ticks, Bound.MAX_VALUE)),
                    n.deadline) <= 0;
        }
        long horizon = Math.max(ticks, Math.max(2 * n.allowedUntil, semantics.ticksPerUnit()));
        int latest = latest(reach(n, horizon));
        if (latest == Bound.INFINITY || Bound.compare(latest, Bound.le((int) Math.min(horizon, Bound.MAX_VALUE))) >= 0) {
            n.allowedUntil = horizon;
            return true;
        }
        n.deadline = latest;
        return Bound.compare(Bound.le((int) Math.min(ticks, Bound.MAX_VALUE)), latest) <= 0;
    }

    /** The raw bound of the latest elapsed time of {@code states} (their zones' upper bounds on the elapsed clock). */
    public int latest(List<SymState> states) {
        int latest = Bound.LT_ZERO;
        for (SymState s : states) {
            int b = s.zone().upperBound(elapsed, 0);
            if (Bound.compare(b, latest) > 0) {
                latest = b;
            }
        }
        return latest;
    }

    /**
     * Every state the closed network can be in (its reachable symbolic states, each closed under delay) with the
     * elapsed clock at 0, those {@code keep} accepts; explored with the same semantics as the events.
     *
     * @throws UnsupportedModelException past {@link #MAX_STATES} states or {@link #REACHABLE_NANOS}
     */
    public Node reachable(Predicate<SymState> keep) {
        long began = System.nanoTime();
        Passed passed = new Passed();
        Deque<SymState> waiting = new ArrayDeque<>();
        waiting.add(semantics.initial());
        Semantics.MoveSink sink = (move, next) -> waiting.add(next);
        while (!waiting.isEmpty()) {
            SymState s = waiting.poll();
            if (!all.delay(s, elapsed, Bound.INFINITY)) {
                continue;
            }
            s.zone().reset(elapsed, 0);
            all.extrapolate(s);
            if (!passed.add(s)) {
                continue;
            }
            if (passed.size() > MAX_STATES || passed.size() % 1024 == 0
                    && System.nanoTime() - began > REACHABLE_NANOS) {
                throw new UnsupportedModelException("the model has too many reachable symbolic states to start from"
                        + " all of them (" + passed.size() + " found in " + (System.nanoTime() - began) / 1_000_000
                        + " ms)");
            }
            all.moves(s, sink);
        }
        List<SymState> kept = new ArrayList<>();
        for (SymState s : passed.states()) {
            if (keep.test(s)) {
                kept.add(s);
            }
        }
        return node(kept);
    }

    /** A key of an event's transition: channel, values and delay window; reused as the probe of lookups. */
    private static final class TransitionKey {
        int channel;
        int[] values;
        long fromTicks;
        long toTicks;
        boolean keepWhen;
        int hash;

        TransitionKey set(int channel, int[] values, long fromTicks, long toTicks, boolean keepWhen) {
            this.channel = channel;
            this.values = values;
            this.fromTicks = fromTicks;
            this.toTicks = toTicks;
            this.keepWhen = keepWhen;
            long h = (((31L * channel + Arrays.hashCode(values)) * 31 + fromTicks) * 31 + toTicks) * 2
                    + (keepWhen ? 1 : 0);
            // mixed (MurmurHash3's finaliser): the sum alone is a multiple of 32 plus the channel's part when the
            // window is one delay, so a node's transitions on one channel fell into a few of the map's buckets
            h = (h ^ (h >>> 33)) * 0xff51afd7ed558ccdL;
            h = (h ^ (h >>> 33)) * 0xc4ceb9fe1a85ec53L;
            this.hash = (int) (h ^ (h >>> 33));
            return this;
        }

        TransitionKey copy() {
            return new TransitionKey().set(channel, values.clone(), fromTicks, toTicks, keepWhen);
        }

        @Override
        public boolean equals(Object o) {
            return o instanceof TransitionKey k && k.hash == hash && k.channel == channel && k.fromTicks == fromTicks
                    && k.toTicks == toTicks && k.keepWhen == keepWhen && Arrays.equals(k.values, values);
        }

        @Override
        public int hashCode() {
            return hash;
        }
    }

    /** A set's states as a hash key: equal when the states are equal, in order. */
    private static final class NodeKey {
        final List<SymState> states;
        final int hash;

        NodeKey(List<SymState> states) {
            this.states = states;
            int h = 1;
            for (SymState s : states) {
                h = 31 * h + 31 * s.discreteHash() + s.zone().hashCode();
            }
            this.hash = h;
        }

        @Override
        public boolean equals(Object o) {
            if (!(o instanceof NodeKey k) || k.hash != hash || k.states.size() != states.size()) {
                return false;
            }
            for (int i = 0; i < states.size(); i++) {
                SymState a = states.get(i);
                SymState b = k.states.get(i);
                if (!a.sameDiscrete(b) || !a.zone().equals(b.zone())) {
                    return false;
                }
            }
            return true;
        }

        @Override
        public int hashCode() {
            return hash;
        }
    }

    /**
     * States compared by zone inclusion with those of the same discrete part: one list scanned while it is short
     * (the sets of one event hold a few states), grouped by discrete part once it grows.
     */
    private static final class Passed {
        /** How many states are scanned in one list before they are grouped. */
        private static final int SCANNED = 16;
        /** The states in the order they were added; null where a later one covered the state. */
        private final List<SymState> order = new ArrayList<>();
        /** Per discrete hash, the indices in {@link #order} of its states not covered; null while few. */
        private Map<Integer, List<Integer>> groups;
        private int dropped;

        /** Adds {@code s} unless a state of its discrete part covers it; drops the states it covers. */
        boolean add(SymState s) {
            if (groups == null && order.size() >= SCANNED) {
                groups = new HashMap<>();
                for (int i = 0; i < order.size(); i++) {
                    SymState o = order.get(i);
                    if (o != null) {
                        groups.computeIfAbsent(o.discreteHash(), k -> new ArrayList<>(2)).add(i);
                    }
                }
            }
            if (groups == null) {
                // one pass: the states kept cover none of each other, so once one is within s, none covers s
                for (int i = 0; i < order.size(); i++) {
                    SymState o = order.get(i);
                    if (o == null || !o.sameDiscrete(s)) {
                        continue;
                    }
                    Relation r = s.zone().relation(o.zone());
                    if (r == Relation.SUBSET || r == Relation.EQUAL) {
                        return false;
                    }
                    if (r == Relation.SUPERSET) {
                        order.set(i, null);
                        dropped++;
                    }
                }
                order.add(s);
                return true;
            }
            List<Integer> group = groups.computeIfAbsent(s.discreteHash(), k -> new ArrayList<>(2));
            for (int i : group) {
                SymState o = order.get(i);
                if (o.sameDiscrete(s) && s.zone().isSubsetOf(o.zone())) {
                    return false;
                }
            }
            group.removeIf(i -> {
                SymState o = order.get(i);
                if (o.sameDiscrete(s) && o.zone().isSubsetOf(s.zone())) {
                    order.set(i, null);
                    dropped++;
                    return true;
                }
                return false;
            });
            group.add(order.size());
            order.add(s);
            return true;
        }

        int size() {
            return order.size() - dropped;
        }

        /** The states added and not covered by a later one, in the order they were added. */
        List<SymState> states() {
            if (dropped == 0) {
                return order;
            }
            List<SymState> kept = new ArrayList<>(order.size() - dropped);
            for (SymState s : order) {
                if (s != null) {
                    kept.add(s);
                }
            }
            return kept;
        }
    }
}
