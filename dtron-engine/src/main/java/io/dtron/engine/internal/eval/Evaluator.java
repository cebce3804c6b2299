package io.dtron.engine.internal.eval;

import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Expression;
import io.dtron.model.Network;
import io.dtron.model.Type;
import java.util.IdentityHashMap;
import java.util.Map;
import java.util.Objects;

/**
 * Evaluates the expressions of one {@link Network}: data expressions, updates (with their clock resets),
 * synchronisation channels, guards and invariants (on zones). Each expression is compiled on first use and
 * cached by identity; evaluating allocates nothing.
 *
 * <p>{@code vars} is the integer state vector (laid out as {@link Network#variables()}), changed in place by
 * updates. {@code frame} holds the values of the edge's select bindings in their slots (null when there are
 * none); it is copied, never changed. Model errors are {@link ModelRuntimeException}s; a state vector may be
 * partly updated when one is thrown. Calls nested deeper than the Java stack allows are a model error too.
 *
 * <p>Not thread-safe: one evaluator per thread.
 */
public final class Evaluator {
    private final Env env;
    private final Compiler compiler;
    private final Map<Expression, Handle> cache = new IdentityHashMap<>();

    /**
     * One expression of the network with its compiled forms, made as they are first needed: callers that keep
     * it evaluate the expression without looking it up again. Valid only with the evaluator that gave it.
     */
    public static final class Handle {
        private final Expression expression;
        private ValueNode value;
        private Conjunction conjunction;
        private PlaceNode channel;
        private int slots;

        private Handle(Expression expression) {
            this.expression = expression;
        }
    }

    /** An evaluator for the expressions of {@code network}. */
    public Evaluator(Network network) {
        this.env = new Env(network);
        this.compiler = new Compiler(network, env);
    }

    /**
     * The value of an integer, boolean (0 or 1) or scalar expression; its assignments, increments and calls
     * take effect on {@code vars}.
     *
     * @throws IllegalArgumentException for clock constraints (see {@link #constrain}) and clock assignments
     *     (see {@link #execute})
     */
    public int evaluate(Expression e, int[] vars, int[] frame) {
        Handle c = valueOf(handle(e));
        env.begin(vars, frame, c.slots, null);
        try {
            return c.value.eval(env);
        } catch (StackOverflowError overflow) {
            throw env.tooDeep();
        }
    }

    /**
     * Executes one update expression: data assignments change {@code vars}; clock assignments (in the update
     * or in the functions it calls) are appended to {@code resets} in order, for the caller to apply.
     */
    public void execute(Expression update, int[] vars, int[] frame, ClockResets resets) {
        execute(handle(update), vars, frame, resets);
    }

    /** {@link #execute(Expression, int[], int[], ClockResets)} of the expression of {@code update}. */
    public void execute(Handle update, int[] vars, int[] frame, ClockResets resets) {
        Objects.requireNonNull(resets, "resets");
        Handle c = valueOf(update);
        env.begin(vars, frame, c.slots, resets);
        try {
            c.value.eval(env);
        } catch (StackOverflowError overflow) {
            throw env.tooDeep();
        }
    }

    /** The channel number of a synchronisation's channel expression. */
    public int channel(Expression channel, int[] vars, int[] frame) {
        return channel(handle(channel), vars, frame);
    }

    /** {@link #channel(Expression, int[], int[])} of the expression of {@code channel}. */
    public int channel(Handle channel, int[] vars, int[] frame) {
        Handle c = channel;
        if (c.channel == null) {
            Expression e = c.expression;
            if (!(e.type() instanceof Type.Channel)) {
                throw new IllegalArgumentException("'" + e.pos().text() + "' is not a channel");
            }
            compiler.beginRoot();
            c.channel = compiler.place(e);
            c.slots = Math.max(c.slots, compiler.rootSlots());
        }
        env.begin(vars, frame, c.slots, null);
        try {
            return c.channel.address(env);
        } catch (StackOverflowError overflow) {
            throw env.tooDeep();
        }
    }

    /**
     * Intersects {@code zone} with a guard or invariant (null is true): its data conjuncts are evaluated first,
     * and when one is false the zone is left alone; then each clock bound is applied, its value scaled by
     * {@code ticksPerUnit}.
     *
     * @return false when a data conjunct is false or the zone became empty
     */
    public boolean constrain(Expression guard, int[] vars, int[] frame, Dbm zone, int ticksPerUnit) {
        return constrain(guard == null ? null : handle(guard), vars, frame, zone, ticksPerUnit);
    }

    /** {@link #constrain(Expression, int[], int[], Dbm, int)} of the expression of {@code guard} (null is true). */
    public boolean constrain(Handle guard, int[] vars, int[] frame, Dbm zone, int ticksPerUnit) {
        if (guard == null) {
            return !zone.isEmpty();
        }
        Handle c = conjunctionOf(guard);
        env.begin(vars, frame, c.slots, null);
        try {
            return c.conjunction.constrain(env, zone, checkTicks(ticksPerUnit));
        } catch (StackOverflowError overflow) {
            throw env.tooDeep();
        }
    }

    /** Whether the data conjuncts of a guard or invariant hold (null is true); clock bounds are ignored. */
    public boolean dataHolds(Expression guard, int[] vars, int[] frame) {
        return dataHolds(guard == null ? null : handle(guard), vars, frame);
    }

    /** {@link #dataHolds(Expression, int[], int[])} of the expression of {@code guard} (null is true). */
    public boolean dataHolds(Handle guard, int[] vars, int[] frame) {
        if (guard == null) {
            return true;
        }
        Handle c = conjunctionOf(guard);
        env.begin(vars, frame, c.slots, null);
        try {
            return c.conjunction.dataHolds(env);
        } catch (StackOverflowError overflow) {
            throw env.tooDeep();
        }
    }

    /**
     * Appends the clock bounds of a guard or invariant (null has none) to {@code out}, in ticks, when its data
     * conjuncts hold; {@code x == c} gives two bounds.
     *
     * @return false (and nothing appended) when a data conjunct is false
     */
    public boolean clockBounds(Expression guard, int[] vars, int[] frame, int ticksPerUnit, ClockBounds out) {
        return clockBounds(guard == null ? null : handle(guard), vars, frame, ticksPerUnit, out);
    }

    /** {@link #clockBounds(Expression, int[], int[], int, ClockBounds)} of the expression of {@code guard}. */
    public boolean clockBounds(Handle guard, int[] vars, int[] frame, int ticksPerUnit, ClockBounds out) {
        if (guard == null) {
            return true;
        }
        Handle c = conjunctionOf(guard);
        env.begin(vars, frame, c.slots, null);
        try {
            return c.conjunction.bounds(env, checkTicks(ticksPerUnit), out);
        } catch (StackOverflowError overflow) {
            throw env.tooDeep();
        }
    }

    private static int checkTicks(int ticksPerUnit) {
        if (ticksPerUnit < 1) {
            throw new IllegalArgumentException("ticks per unit must be positive: " + ticksPerUnit);
        }
        return ticksPerUnit;
    }

    /**
     * The handle of {@code e}, to evaluate it without looking it up each time; nothing is compiled until the
     * handle is first used (a model error in {@code e} is reported then, as by the methods taking expressions).
     */
    public Handle handle(Expression e) {
        Handle c = cache.get(Objects.requireNonNull(e, "expression"));
        if (c == null) {
            c = new Handle(e);
            cache.put(e, c);
        }
        return c;
    }

    private Handle valueOf(Handle c) {
        if (c.value == null) {
            compiler.beginRoot();
            c.value = compiler.value(c.expression);
            c.slots = Math.max(c.slots, compiler.rootSlots());
        }
        return c;
    }

    private Handle conjunctionOf(Handle c) {
        if (c.conjunction == null) {
            compiler.beginRoot();
            c.conjunction = compiler.conjunction(c.expression);
            c.slots = Math.max(c.slots, compiler.rootSlots());
        }
        return c;
    }
}
