package io.dtron.engine.internal.sem;

import io.dtron.engine.internal.eval.ClockBounds;
import io.dtron.engine.internal.eval.ClockResets;
import io.dtron.engine.internal.eval.Evaluator;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.function.IntPredicate;

/**
 * Delays and successors of many states of one {@link Semantics}, with the work that depends only on a state's
 * discrete part (locations and variables) done once per discrete part: which moves are possible (data guards,
 * channels, committed locations), the updates of each move, and the clock bounds of its guards and of the
 * invariants, which are then applied to each zone as plain constraints. Each state gets exactly what
 * {@link Semantics#delay} and {@link Semantics#moves} give it, in the same order; where listing the bounds
 * ahead could report a model error that applying them one by one would not (or the other way round), that
 * move or location is handled by {@link Semantics} itself, state by state.
 *
 * <p>It keeps what it learned until it holds more discrete parts than its limit, then starts again. Not
 * thread-safe.
 */
public final class DiscreteCache {
    private static final byte UNKNOWN = 0;
    private static final byte LISTED = 1;
    /** Handled state by state by {@link Semantics}. */
    private static final byte SLOW = 2;

    private final Semantics semantics;
    private final Evaluator evaluator;
    private final int ticksPerUnit;
    private final IntPredicate channels;
    private final int limit;
    private final Map<Key, Entry> entries = new HashMap<>();
    private final ClockBounds bounds = new ClockBounds();
    private final ClockResets resets = new ClockResets();
    /** The entries met last, by their hash: a lookup without allocating a key. */
    private final Entry[] recent = new Entry[4096];

    /**
     * A cache for the moves on the channels {@code channels} accepts (-1 for an edge without synchronisation),
     * forgetting all when it holds more than {@code limit} discrete parts.
     */
    public DiscreteCache(Semantics semantics, IntPredicate channels, int limit) {
        this.semantics = semantics;
        this.limit = limit;
        this.evaluator = semantics.evaluator();
        this.ticksPerUnit = semantics.ticksPerUnit();
        this.channels = channels;
    }

    /** What is known of one discrete part. */
    private static final class Entry {
        final int[] locations;
        final int[] vars;
        final int hash;
        /** 0 unknown, 1 time may pass, 2 it may not. */
        byte mayDelay;
        byte invariantState = UNKNOWN;
        int[] invariant;
        /** {@link #invariant} and room for one more bound, for {@link #delay}. */
        int[] invariantAndBound;
        List<Template> templates;
        /** {@link Semantics#extrapolationBounds} of the locations, once asked for. */
        int[] extrapolation;
        boolean extrapolationKnown;

        Entry(int[] locations, int[] vars, int hash) {
            this.locations = locations;
            this.vars = vars;
            this.hash = hash;
        }
    }

    /** One move of a discrete part. */
    private static final class Template {
        final List<Semantics.Candidate> participants;
        final int channel;
        byte guardState = UNKNOWN;
        int[] guard;
        /** Set once the updates have run. */
        Semantics.Move move;
        int[] locations;
        int[] vars;
        int hash;
        int[] resetClocks;
        int[] resetTicks;
        /** Per clock, the value in ticks the move last assigns it, or -1. */
        int[] resetOf;
        Entry target;
        /**
         * The target's invariant bounds that a zone satisfying the source's invariants may not satisfy after the
         * move: those the source does not have and those on a clock the move assigns; null until needed.
         */
        int[] newInvariant;

        Template(List<Semantics.Candidate> participants, int channel) {
            this.participants = participants;
            this.channel = channel;
        }
    }

    private record Key(int[] locations, int[] vars, int hash) {
        @Override
        public boolean equals(Object o) {
            return o instanceof Key k && hash == k.hash && Arrays.equals(locations, k.locations)
                    && Arrays.equals(vars, k.vars);
        }

        @Override
        public int hashCode() {
            return hash;
        }
    }

    /**
     * {@link Semantics#delay(SymState)}, then the upper bound {@code x_clock ⋈ value(bound)} (raw), added together
     * with the invariants; false if nothing is left.
     */
    public boolean delay(SymState s, int clock, int bound) {
        Entry e = entry(s.locations, s.vars, s.discreteHash());
        if (e.mayDelay == 0) {
            e.mayDelay = semantics.mayDelay(s) ? (byte) 1 : (byte) 2;
        }
        if (e.mayDelay == 1) {
            s.zone.up();
        }
        if (e.invariantState == UNKNOWN) {
            listInvariants(e);
        }
        if (e.invariantState == SLOW) {
            return semantics.invariants(e.locations, e.vars, s.zone) && s.zone.constrain(clock, 0, bound);
        }
        int[] triples = e.invariantAndBound;
        if (triples == null) {
            triples = Arrays.copyOf(e.invariant, e.invariant.length + 3);
            e.invariantAndBound = triples;
        }
        triples[triples.length - 3] = clock;
        triples[triples.length - 2] = 0;
        triples[triples.length - 1] = bound;
        return s.zone.constrainAll(triples) && !s.zone.isEmpty();
    }

    /** {@link Semantics#extrapolate(SymState)}, with the bounds of the state's locations remembered. */
    public void extrapolate(SymState s) {
        Entry e = entry(s.locations, s.vars, s.discreteHash());
        if (!e.extrapolationKnown) {
            e.extrapolation = semantics.extrapolationBounds(e.locations);
            e.extrapolationKnown = true;
        }
        semantics.extrapolate(s, e.extrapolation);
    }

    /** {@link Semantics#moves(SymState, IntPredicate, Semantics.MoveSink)} with this cache's channels. */
    public void moves(SymState s, Semantics.MoveSink sink) {
        for (Template t : templates(s)) {
            fire(s, t, sink);
        }
    }

    /**
     * {@link #moves(SymState, Semantics.MoveSink)}, only those on channel {@code channel} (one this cache's
     * channels include): the same as a cache for that channel alone gives.
     */
    public void moves(SymState s, int channel, Semantics.MoveSink sink) {
        for (Template t : templates(s)) {
            if (t.channel == channel) {
                fire(s, t, sink);
            }
        }
    }

    /**
     * {@link #moves(SymState, Semantics.MoveSink)}, only those on the channels {@code channels} accepts (-1 for an
     * edge without synchronisation): the same as a cache for those channels gives, so that one cache serves
     * several sets of channels.
     */
    public void moves(SymState s, IntPredicate channels, Semantics.MoveSink sink) {
        for (Template t : templates(s)) {
            if (channels.test(t.channel)) {
                fire(s, t, sink);
            }
        }
    }

    /**
     * Whether the discrete part of {@code s} has a move on channel {@code channel} whose data guard holds and whose
     * successor's variables hold {@code values} at {@code slots}: false when {@link #moves(SymState, int,
     * Semantics.MoveSink)} gives no successor with those values whatever the zone (a move's updates, and so its
     * successor's variables, depend on the discrete part only).
     */
    public boolean mayMove(SymState s, int channel, int[] slots, int[] values) {
        for (Template t : templates(s)) {
            if (t.channel != channel) {
                continue;
            }
            if (t.guardState == UNKNOWN) {
                listGuards(s, t);
            }
            if (t.guardState == SLOW) {
                return true;
            }
            if (t.guard == null) {
                continue;
            }
            if (t.move == null) {
                try {
                    prepare(s, t);
                } catch (ModelRuntimeException e) {
                    return true; // fire reports it where the zone allows the move, as before
                }
            }
            if (holds(t.vars, slots, values)) {
                return true;
            }
        }
        return false;
    }

    private static boolean holds(int[] vars, int[] slots, int[] values) {
        for (int i = 0; i < slots.length; i++) {
            if (vars[slots[i]] != values[i]) {
                return false;
            }
        }
        return true;
    }

    private List<Template> templates(SymState s) {
        Entry e = entry(s.locations, s.vars, s.discreteHash());
        if (e.templates == null) {
            List<Template> templates = new ArrayList<>();
            semantics.enumerate(s, channels, (participants, channel) ->
                    templates.add(new Template(participants, channel)));
            e.templates = templates;
        }
        return e.templates;
    }

    /** Receives the bounds of one clock in a successor: the move, the raw bounds of the clock and of minus it. */
    public interface ClockSink {
        /** {@code upper} is the successor zone's raw bound of {@code x - 0}, {@code lowerNeg} that of {@code 0 - x}. */
        void accept(Semantics.Move move, int upper, int lowerNeg);
    }

    /**
     * For every successor {@link #moves} gives {@code s}, in the same order, the bounds of {@code clock} in its
     * zone; {@code clock} must be one no update assigns (the tester's clock). Where at most one clock bound of
     * the guards constrains the zone and the invariants after the move constrain nothing, the bounds are read
     * off the zone of {@code s} without building the successor.
     */
    public void clockBounds(SymState s, int clock, ClockSink sink) {
        List<Template> templates = templates(s);
        Entry e = entry(s.locations, s.vars, s.discreteHash());
        boolean invariantsHold = e.invariantState == LISTED && satisfies(s.zone, e.invariant);
        for (Template t : templates) {
            if (!quickBounds(s, e, invariantsHold, t, clock, sink)) {
                fire(s, t, (move, next) -> sink.accept(move, next.zone.upperBound(clock, 0),
                        next.zone.upperBound(0, clock)));
            }
        }
    }

    /**
     * The bounds of {@code clock} after {@code t} from {@code s} without building the successor (handed to
     * {@code sink} unless the move is impossible); false when that cannot be done and the move must be fired.
     */
    private boolean quickBounds(SymState s, Entry source, boolean invariantsHold, Template t, int clock,
                                ClockSink sink) {
        if (t.guardState == UNKNOWN) {
            listGuards(s, t);
        }
        if (t.guardState == SLOW) {
            return false;
        }
        if (t.guard == null) {
            return true;
        }
        Dbm z = s.zone;
        if (z.isEmpty()) {
            return true;
        }
        // the zone and at most one constraint x_a - x_b <= c of the guards that it does not imply
        int a = -1;
        int b = -1;
        int c = 0;
        int[] g = t.guard;
        for (int k = 0; k < g.length; k += 3) {
            int i = g[k];
            int j = g[k + 1];
            if (entry(z, a, b, c, i, j) <= g[k + 2]) {
                continue;
            }
            if (a >= 0) {
                return false;
            }
            if (Bound.add(g[k + 2], entry(z, a, b, c, j, i)) < Bound.LE_ZERO) {
                return true;
            }
            a = i;
            b = j;
            c = g[k + 2];
        }
        if (t.move == null) {
            prepare(s, t);
        }
        Entry target = t.target;
        if (target.invariantState == UNKNOWN) {
            listInvariants(target);
        }
        if (target.invariantState == SLOW) {
            return false;
        }
        if (invariantsHold && t.newInvariant == null) {
            t.newInvariant = newBounds(source.invariant, target.invariant, t.resetOf);
        }
        // the zone after the guard is within that of s: bounds it satisfies hold there too
        int[] inv = invariantsHold ? t.newInvariant : target.invariant;
        for (int k = 0; k < inv.length; k += 3) {
            if (afterResets(z, a, b, c, t, inv[k], inv[k + 1]) > inv[k + 2]) {
                return false;
            }
        }
        sink.accept(t.move, entry(z, a, b, c, clock, 0), entry(z, a, b, c, 0, clock));
        return true;
    }

    /** Whether {@code z} satisfies every bound of {@code triples}. */
    private static boolean satisfies(Dbm z, int[] triples) {
        for (int k = 0; k < triples.length; k += 3) {
            if (z.upperBound(triples[k], triples[k + 1]) > triples[k + 2]) {
                return false;
            }
        }
        return true;
    }

    /** The bounds of {@code target} not in {@code source} or on a clock {@code resetOf} assigns. */
    private static int[] newBounds(int[] source, int[] target, int[] resetOf) {
        int[] out = new int[target.length];
        int n = 0;
        for (int k = 0; k < target.length; k += 3) {
            boolean keep = resetOf[target[k]] >= 0 || resetOf[target[k + 1]] >= 0
                    || !contains(source, target[k], target[k + 1], target[k + 2]);
            if (keep) {
                out[n++] = target[k];
                out[n++] = target[k + 1];
                out[n++] = target[k + 2];
            }
        }
        return Arrays.copyOf(out, n);
    }

    private static boolean contains(int[] triples, int i, int j, int b) {
        for (int k = 0; k < triples.length; k += 3) {
            if (triples[k] == i && triples[k + 1] == j && triples[k + 2] == b) {
                return true;
            }
        }
        return false;
    }

    /** Entry (i, j) of the closure of {@code z} and x_a - x_b <= c (of {@code z} alone when a is -1). */
    private static int entry(Dbm z, int a, int b, int c, int i, int j) {
        int old = z.upperBound(i, j);
        if (a < 0) {
            return old;
        }
        int via = Bound.add(Bound.add(z.upperBound(i, a), c), z.upperBound(b, j));
        return Math.min(old, via);
    }

    /** Entry (i, j) of that zone after the resets of {@code t}, as {@link Dbm#reset} computes it. */
    private static int afterResets(Dbm z, int a, int b, int c, Template t, int i, int j) {
        if (i == j) {
            return Bound.LE_ZERO;
        }
        int vi = t.resetOf[i];
        int vj = t.resetOf[j];
        int base = entry(z, a, b, c, vi < 0 ? i : 0, vj < 0 ? j : 0);
        int out = vi < 0 ? base : Bound.add(Bound.le(vi), base);
        return vj < 0 ? out : Bound.add(out, Bound.le(-vj));
    }

    private void fire(SymState s, Template t, Semantics.MoveSink sink) {
        if (t.guardState == UNKNOWN) {
            listGuards(s, t);
        }
        if (t.guardState == SLOW) {
            semantics.fire(s, t.participants, t.channel, sink);
            return;
        }
        if (t.guard == null) {
            return;
        }
        Dbm zone = s.zone.copy();
        if (!constrain(zone, t.guard) || zone.isEmpty()) {
            return;
        }
        if (t.move == null) {
            prepare(s, t);
        }
        for (int i = 0; i < t.resetClocks.length; i++) {
            zone.reset(t.resetClocks[i], t.resetTicks[i]);
        }
        if (!invariants(t.target, zone)) {
            return;
        }
        sink.accept(t.move, new SymState(t.locations, t.vars, zone, t.hash));
    }

    /** The clock bounds of the participants' guards (null when a data conjunct is false), or SLOW. */
    private void listGuards(SymState s, Template t) {
        bounds.clear();
        try {
            for (Semantics.Candidate c : t.participants) {
                if (c.guard() != null && !evaluator.clockBounds(c.guard(), s.vars, c.frame(), ticksPerUnit, bounds)) {
                    t.guardState = LISTED;
                    return;
                }
            }
        } catch (ModelRuntimeException e) {
            t.guardState = SLOW;
            return;
        }
        t.guard = toArray(bounds);
        t.guardState = LISTED;
    }

    /** Runs the updates of {@code t} on the variables of {@code s}: its target discrete part and resets. */
    private void prepare(SymState s, Template t) {
        int[] vars = s.vars.clone();
        int[] clocks;
        int[] ticks;
        resets.clear();
        try {
            for (Semantics.Candidate c : t.participants) {
                for (Evaluator.Handle update : c.updates()) {
                    evaluator.execute(update, vars, c.frame(), resets);
                }
            }
            clocks = new int[resets.size()];
            ticks = new int[resets.size()];
            for (int i = 0; i < clocks.length; i++) {
                clocks[i] = resets.clock(i);
                ticks[i] = resets.ticks(i, ticksPerUnit);
            }
        } finally {
            resets.clear();
        }
        int[] locations = s.locations.clone();
        Semantics.Step[] steps = new Semantics.Step[t.participants.size()];
        for (int i = 0; i < steps.length; i++) {
            Semantics.Candidate c = t.participants.get(i);
            locations[c.process()] = c.edge().target();
            steps[i] = new Semantics.Step(c.process(), c.edge(), c.frame());
        }
        t.locations = locations;
        t.vars = vars;
        t.hash = 31 * Arrays.hashCode(locations) + Arrays.hashCode(vars);
        t.resetClocks = clocks;
        t.resetTicks = ticks;
        t.resetOf = new int[s.zone.dimension()];
        Arrays.fill(t.resetOf, -1);
        for (int i = 0; i < clocks.length; i++) {
            t.resetOf[clocks[i]] = ticks[i];
        }
        t.target = entry(locations, vars, t.hash);
        t.move = new Semantics.Move(t.channel, List.of(steps));
    }

    /** {@link Semantics#invariants} of the discrete part {@code e} on {@code zone}. */
    private boolean invariants(Entry e, Dbm zone) {
        if (e.invariantState == UNKNOWN) {
            listInvariants(e);
        }
        if (e.invariantState == SLOW) {
            return semantics.invariants(e.locations, e.vars, zone);
        }
        return constrain(zone, e.invariant) && !zone.isEmpty();
    }

    private void listInvariants(Entry e) {
        bounds.clear();
        try {
            for (int p = 0; p < e.locations.length; p++) {
                Evaluator.Handle inv = semantics.invariantOf(p, e.locations[p]);
                if (inv != null && !evaluator.clockBounds(inv, e.vars, null, ticksPerUnit, bounds)) {
                    // false whatever the zone; the zone is then left as Semantics leaves it
                    e.invariantState = SLOW;
                    return;
                }
            }
        } catch (ModelRuntimeException ex) {
            e.invariantState = SLOW;
            return;
        }
        e.invariant = toArray(bounds);
        e.invariantState = LISTED;
    }

    private static boolean constrain(Dbm zone, int[] triples) {
        return zone.constrainAll(triples);
    }

    private static int[] toArray(ClockBounds b) {
        int[] out = new int[3 * b.size()];
        for (int k = 0; k < b.size(); k++) {
            out[3 * k] = b.i(k);
            out[3 * k + 1] = b.j(k);
            out[3 * k + 2] = b.bound(k);
        }
        return out;
    }

    private Entry entry(int[] locations, int[] vars, int hash) {
        int slot = (hash ^ hash >>> 16) & (recent.length - 1);
        Entry e = recent[slot];
        // the successors of one move share its arrays: most lookups end at the identity test
        if (e != null && (e.locations == locations && e.vars == vars
                || e.hash == hash && Arrays.equals(e.locations, locations) && Arrays.equals(e.vars, vars))) {
            return e;
        }
        if (entries.size() >= limit) {
            entries.clear();
            Arrays.fill(recent, null);
        }
        e = entries.computeIfAbsent(new Key(locations, vars, hash), k -> new Entry(k.locations, k.vars, k.hash));
        recent[slot] = e;
        return e;
    }
}
