package io.dtron.engine.internal.eval;

import io.dtron.engine.zone.Dbm;
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
    private final Map<Expression, Compiled> cache = new IdentityHashMap<>();

    /** The compiled forms of one expression, made as they are first needed. */
    private static final class Compiled {
        ValueNode value;
        Conjunction conjunction;
        PlaceNode channel;
        int slots;
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
        Compiled c = valueOf(e);
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
        Objects.requireNonNull(resets, "resets");
        Compiled c = valueOf(update);
        env.begin(vars, frame, c.slots, resets);
        try {
            c.value.eval(env);
        } catch (StackOverflowError overflow) {
            throw env.tooDeep();
        }
    }

    /** The channel number of a synchronisation's channel expression. */
    public int channel(Expression channel, int[] vars, int[] frame) {
        Compiled c = cache.get(channel);
        if (c == null || c.channel == null) {
            if (!(channel.type() instanceof Type.Channel)) {
                throw new IllegalArgumentException("'" + channel.pos().text() + "' is not a channel");
            }
            c = compiled(channel);
            compiler.beginRoot();
            c.channel = compiler.place(channel);
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
        if (guard == null) {
            return !zone.isEmpty();
        }
        Compiled c = conjunctionOf(guard);
        env.begin(vars, frame, c.slots, null);
        try {
            return c.conjunction.constrain(env, zone, checkTicks(ticksPerUnit));
        } catch (StackOverflowError overflow) {
            throw env.tooDeep();
        }
    }

    /** Whether the data conjuncts of a guard or invariant hold (null is true); clock bounds are ignored. */
    public boolean dataHolds(Expression guard, int[] vars, int[] frame) {
        if (guard == null) {
            return true;
        }
        Compiled c = conjunctionOf(guard);
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
        if (guard == null) {
            return true;
        }
        Compiled c = conjunctionOf(guard);
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

    private Compiled valueOf(Expression e) {
        Compiled c = cache.get(e);
        if (c == null || c.value == null) {
            c = compiled(e);
            compiler.beginRoot();
            c.value = compiler.value(e);
            c.slots = Math.max(c.slots, compiler.rootSlots());
        }
        return c;
    }

    private Compiled conjunctionOf(Expression e) {
        Compiled c = cache.get(e);
        if (c == null || c.conjunction == null) {
            c = compiled(e);
            compiler.beginRoot();
            c.conjunction = compiler.conjunction(e);
            c.slots = Math.max(c.slots, compiler.rootSlots());
        }
        return c;
    }

    private Compiled compiled(Expression e) {
        return cache.computeIfAbsent(e, k -> new Compiled());
    }
}
