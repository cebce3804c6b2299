package io.dtron.engine.sim;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.PartitionException;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Random;
import java.util.function.IntPredicate;

/**
 * The implementation part of a model run as the system under test, in the tester's process: a concrete
 * simulation of the processes on the implementation's side of the test interface (Uppaal TRON's partition), with
 * concrete clock values in the tester's ticks. It applies each input the tester performs on a receiving edge that
 * is enabled (one chosen at random when several are; an input none accepts is ignored, as an input-enabled system
 * ignores it), and between inputs chooses, with its own seed, one of its next moves (an output or an internal
 * move) and a time at which the move is enabled and the invariants hold (a quarter of the time the earliest, a
 * quarter the latest, else any, in whole ticks of the tester), or to wait for the next input when its invariants
 * let it wait for ever. Urgent and committed locations and urgent channels take no time. Run on the
 * model it was made from it never contradicts the model; run on a {@link Mutants mutant}, it is the faulty system.
 */
public final class ModelSystem implements Adapter {
    /** The most moves the system makes at one instant before it gives up as Zeno. */
    static final int MAX_MOVES_AT_ONE_INSTANT = 10_000;
    /** How the reason starts when the system meets an error of its model (an update out of a variable's range). */
    public static final String MODEL_ERROR = "the model as system under test met a model error: ";

    private final Network network;
    private final TestInterface testInterface;
    private final Random random;
    private final boolean[] inside;
    private final IntPredicate insideTest;
    private final int[] channelKind;
    private final Map<Integer, TestInterface.ObservableChannel> outputs = new LinkedHashMap<>();
    private final long horizonUnits;

    private AdapterContext context;
    private TestClock clock;
    private Semantics semantics;
    private long unitMicros;
    private int ticksPerUnit;
    /** Delays are multiples of this many ticks, so that each is a whole number of microseconds. */
    private long tickStep;
    private int elapsed;
    /** The current concrete state (a point zone whose elapsed clock is the time since {@link #stateMicros}). */
    private SymState state;
    private long stateMicros;
    private TestClock.Scheduled pending;
    private int movesAtInstant;
    private long instant = -1;
    private boolean stopped;

    /**
     * The implementation part of {@code network}, split from its environment by {@code testInterface}, choosing
     * with {@code seed}.
     *
     * @throws UnsupportedModelException when the interface does not split the model (and from {@link #start} when
     *                                   the engine cannot run it)
     */
    public ModelSystem(Network network, TestInterface testInterface, long seed) {
        this.network = Objects.requireNonNull(network, "network");
        this.testInterface = Objects.requireNonNull(testInterface, "testInterface");
        this.random = new Random(seed);
        Partition partition;
        try {
            partition = Partition.of(network, testInterface);
        } catch (PartitionException e) {
            throw new UnsupportedModelException(e.getMessage());
        }
        int n = network.processes().size();
        this.inside = new boolean[n];
        for (int p = 0; p < n; p++) {
            inside[p] = !partition.isEnvironment(p);
        }
        this.insideTest = p -> inside[p];
        this.channelKind = new int[network.channelCount()];
        for (int c = 0; c < channelKind.length; c++) {
            channelKind[c] = partition.observable(c);
        }
        testInterface.outputs().forEach(o -> outputs.put(o.channel(), o));
        this.horizonUnits = Math.max(1, largestConstant(network, inside));
    }

    /**
     * The system's seed for a run with seed {@code runSeed}, when none is given: a fixed function of it, so that a
     * run seed replays the system's choices too.
     */
    public static long seedFor(long runSeed) {
        return runSeed * 0x9E3779B97F4A7C15L + 0x632BE59BD9B4E019L;
    }

    @Override
    public void start(AdapterContext context) {
        this.context = context;
        this.clock = context.clock();
        this.unitMicros = context.timeUnitMicros();
        // the tester's ticks (OnlineTester: at most 1000 per time unit)
        this.ticksPerUnit = (int) Math.min(unitMicros, 1000);
        this.tickStep = ticksPerUnit / gcd(ticksPerUnit, unitMicros);
        this.semantics = new Semantics(network, ticksPerUnit);
        this.elapsed = semantics.elapsedClock();
        SymState initial = semantics.initial();
        int[] locations = new int[network.processes().size()];
        for (int p = 0; p < locations.length; p++) {
            locations[p] = inside[p] ? initial.location(p) : -1;
        }
        int[] vars = network.initialState();
        Dbm zone = Dbm.zero(semantics.dimension());
        if (!semantics.invariants(locations, vars, zone)) {
            throw new UnsupportedModelException("the initial state of the implementation violates an invariant");
        }
        state = SymState.of(locations, vars, zone);
        stateMicros = clock.nowMicros();
        guarded(this::plan);
    }

    @Override
    public void perform(Event input) {
        guarded(() -> apply(input));
    }

    /** Runs a step of the system; a model error stops it and ends the run INCONCLUSIVE, naming the error. */
    private void guarded(Runnable step) {
        try {
            step.run();
        } catch (ModelRuntimeException e) {
            stopped = true;
            cancelPending();
            context.inconclusive(MODEL_ERROR + e.format());
        }
    }

    private void apply(Event input) {
        if (stopped) {
            return;
        }
        TestInterface.ObservableChannel channel = testInterface.input(input.channel()).orElse(null);
        if (channel == null) {
            return;
        }
        cancelPending();
        if (!advanceTo(clock.nowMicros())) {
            return;
        }
        int[] vars = state.vars().clone();
        for (TestInterface.AttachedVariable v : channel.variables()) {
            Integer value = input.values().get(v.name());
            if (value != null) {
                vars[v.variable().offset()] = value;
            }
        }
        SymState given = SymState.of(state.locations(), vars, state.zone());
        List<SymState> next = new ArrayList<>();
        semantics.openMoves(given, insideTest, channel.channel(), false, (move, s) -> next.add(s));
        if (!next.isEmpty()) {
            settle(next.get(random.nextInt(next.size())));
        }
        plan();
    }

    @Override
    public void stop() {
        stopped = true;
        cancelPending();
    }

    // ================================================================ choosing the next move

    /** A move the system may make next: its successor, and the delays (ticks, a multiple of the step) it may wait. */
    private record Option(Semantics.Move move, long earliest, long latest) {
    }

    /** Chooses the next move and its time, and schedules it; or waits for an input. */
    private void plan() {
        if (stopped) {
            return;
        }
        long now = clock.nowMicros();
        if (now != instant) {
            instant = now;
            movesAtInstant = 0;
        }
        if (++movesAtInstant > MAX_MOVES_AT_ONE_INSTANT) {
            stopped = true;
            context.inconclusive("the model as system under test made " + MAX_MOVES_AT_ONE_INSTANT
                    + " moves at one instant (a cycle of its implementation takes no time)");
            return;
        }
        Dbm zone = state.zone().copy();
        SymState delayed = SymState.of(state.locations(), state.vars(), zone);
        boolean mayDelay = semantics.mayDelay(delayed) && !urgentOutputEnabled();
        if (mayDelay) {
            zone.up();
        }
        if (!semantics.invariants(state.locations(), state.vars(), zone)) {
            return; // cannot happen: the state holds its invariants
        }
        int upper = zone.upperBound(elapsed);
        boolean forever = mayDelay && Bound.isInfinite(upper);
        List<Option> options = new ArrayList<>();
        Semantics.MoveSink collect = (move, next) -> {
            Option o = window(move, next.zone());
            if (o != null) {
                options.add(o);
            }
        };
        semantics.moves(delayed, c -> c < 0 || channelKind[c] == Partition.INTERNAL, collect);
        for (int c : outputs.keySet()) {
            semantics.openMoves(delayed, insideTest, c, true, collect);
        }
        int choices = options.size() + (forever || options.isEmpty() ? 1 : 0);
        int pick = random.nextInt(choices);
        if (pick >= options.size()) {
            return; // wait for an input
        }
        Option chosen = options.get(pick);
        long latest = chosen.latest() == Long.MAX_VALUE
                ? chosen.earliest() + horizonUnits * ticksPerUnit : chosen.latest();
        long steps = (latest - chosen.earliest()) / tickStep;
        // a quarter of the time at the window's start, a quarter at its end when it has one, else anywhere in it:
        // a bound that is off by a little shows only near the bound
        int where = random.nextInt(4);
        long delay = chosen.earliest() + tickStep * (steps <= 0 || where == 0 ? 0
                : where == 1 && chosen.latest() != Long.MAX_VALUE ? steps : Math.floorMod(random.nextLong(), steps + 1));
        long at = stateMicros + micros(delay);
        pending = clock.schedule(Math.max(0, at - clock.nowMicros()), () -> guarded(() -> take(chosen.move(), at)));
    }

    /** The delays (in ticks) at which {@code move} may be taken, from its successor's zone; null if none. */
    private Option window(Semantics.Move move, Dbm next) {
        int low = next.lowerBound(elapsed);
        long earliest = Bound.value(low) + (Bound.isStrict(low) ? 1 : 0);
        earliest = ceilTo(Math.max(0, earliest), tickStep);
        int high = next.upperBound(elapsed);
        long latest;
        if (Bound.isInfinite(high)) {
            latest = Long.MAX_VALUE;
        } else {
            latest = Bound.value(high) - (Bound.isStrict(high) ? 1 : 0);
            latest = Math.floorDiv(latest, tickStep) * tickStep;
            if (latest < earliest) {
                return null;
            }
        }
        return new Option(move, earliest, latest);
    }

    /** Takes {@code move} at {@code at}, if it is still enabled then; reports it when it is an output. */
    private void take(Semantics.Move chosen, long at) {
        pending = null;
        if (stopped || !advanceTo(at)) {
            return;
        }
        SymState[] found = {null};
        Semantics.MoveSink match = (move, next) -> {
            if (found[0] == null && same(move, chosen)) {
                found[0] = next;
            }
        };
        if (chosen.channel() >= 0 && channelKind[chosen.channel()] == Partition.OUTPUT) {
            semantics.openMoves(state, insideTest, chosen.channel(), true, match);
        } else {
            semantics.moves(state, c -> c == chosen.channel(), match);
        }
        if (found[0] != null) {
            settle(found[0]);
            TestInterface.ObservableChannel output = chosen.channel() < 0 ? null : outputs.get(chosen.channel());
            if (output != null) {
                Map<String, Integer> values = new LinkedHashMap<>();
                for (TestInterface.AttachedVariable v : output.variables()) {
                    values.put(v.name(), state.var(v.variable().offset()));
                }
                context.report(new Event(output.name(), values));
            }
        }
        plan();
    }

    private static boolean same(Semantics.Move a, Semantics.Move b) {
        if (a.channel() != b.channel() || a.steps().size() != b.steps().size()) {
            return false;
        }
        for (int i = 0; i < a.steps().size(); i++) {
            Semantics.Step x = a.steps().get(i);
            Semantics.Step y = b.steps().get(i);
            if (x.process() != y.process() || x.edge().index() != y.edge().index()
                    || !Arrays.equals(x.frame(), y.frame())) {
                return false;
            }
        }
        return true;
    }

    /** Whether an output on an urgent channel is enabled now (the environment is taken as ready for it). */
    private boolean urgentOutputEnabled() {
        for (int c : outputs.keySet()) {
            if (semantics.isUrgent(c)) {
                boolean[] any = {false};
                semantics.openMoves(state, insideTest, c, true, (move, next) -> any[0] = true);
                if (any[0]) {
                    return true;
                }
            }
        }
        return false;
    }

    // ================================================================ the concrete state

    /** Lets the state's time pass to {@code micros}; false (and the system stops) if its invariants forbid it. */
    private boolean advanceTo(long micros) {
        long ticks = Math.floorDiv((micros - stateMicros) * ticksPerUnit, unitMicros);
        if (ticks <= 0) {
            return true;
        }
        long largest = 0;
        for (int x = 1; x < semantics.dimension(); x++) {
            largest = Math.max(largest, Bound.value(state.zone().upperBound(x)));
        }
        if (largest + ticks > Bound.MAX_VALUE / 2) {
            // zones count ticks in ints: a clock never reset cannot grow for ever
            stopped = true;
            context.inconclusive("the model as system under test cannot count a clock past " + Bound.MAX_VALUE / 2
                    / ticksPerUnit + " time units");
            return false;
        }
        Dbm zone = state.zone().copy();
        zone.up();
        boolean ok = zone.constrain(elapsed, 0, Bound.le((int) ticks)) && zone.constrain(0, elapsed,
                Bound.le((int) -ticks)) && semantics.invariants(state.locations(), state.vars(), zone);
        if (!ok) {
            // the tester let time pass beyond what the implementation's invariants allow: it does nothing more
            stopped = true;
            return false;
        }
        state = SymState.of(state.locations(), state.vars(), zone);
        stateMicros = micros;
        return true;
    }

    /** Makes {@code next} (a successor of the state at its time) the state, its elapsed clock back at 0. */
    private void settle(SymState next) {
        Dbm zone = next.zone();
        zone.reset(elapsed, 0);
        state = next;
    }

    private void cancelPending() {
        if (pending != null) {
            pending.cancel();
            pending = null;
        }
    }

    private long micros(long ticks) {
        return ticks * unitMicros / ticksPerUnit;
    }

    private static long ceilTo(long value, long step) {
        return -Math.floorDiv(-value, step) * step;
    }

    private static long gcd(long a, long b) {
        return b == 0 ? a : gcd(b, a % b);
    }

    /** The largest constant in the implementation's guards and invariants: how far ahead an unbounded choice looks. */
    private static long largestConstant(Network network, boolean[] inside) {
        long[] max = {0};
        for (io.dtron.model.Process p : network.processes()) {
            if (!inside[p.index()]) {
                continue;
            }
            for (Location l : p.locations()) {
                largest(l.invariant(), max);
            }
            p.edges().forEach(e -> largest(e.guard(), max));
        }
        return max[0];
    }

    private static void largest(Expression e, long[] max) {
        if (e instanceof Expression.Constant c) {
            max[0] = Math.max(max[0], Math.abs((long) c.value()));
        } else if (e instanceof Expression.Binary b) {
            largest(b.left(), max);
            largest(b.right(), max);
        } else if (e instanceof Expression.Unary u) {
            largest(u.operand(), max);
        }
    }
}
