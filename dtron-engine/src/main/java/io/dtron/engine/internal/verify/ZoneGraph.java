package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.eval.ClockResets;
import io.dtron.engine.internal.sem.ClockLimits;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Expression;
import java.util.ArrayList;
import java.util.List;

/**
 * The zone graph the checker explores, on the engine's {@link Semantics} (so that checker and tester agree on
 * committed and urgent locations, urgent and broadcast channels, selects and functions): states are closed under
 * delay as the invariants allow, then extrapolated (Extra+_LU for reachability; Extra+_M, which stays within the closure under region
 * equivalence, where {@code deadlock} or liveness is asked). The zones have no tester's clock.
 */
final class ZoneGraph {
    /** How states are extrapolated. */
    enum Abstraction { LU, M, NONE }

    private final Semantics semantics;
    private final int dimension;
    private final int stateSize;
    private final Abstraction abstraction;
    private final ClockLimits limits;
    private final int[] lower;
    private final int[] upper;
    private final ClockResets resets = new ClockResets();

    /** Receives a successor: the move and the delayed, extrapolated state. */
    interface Sink {
        void accept(Semantics.Move move, SymState next);
    }

    ZoneGraph(Semantics semantics, ClockLimits limits, boolean regionPreserving) {
        this.semantics = semantics;
        this.dimension = semantics.dimension();
        this.stateSize = semantics.network().stateSize();
        this.abstraction = limits == null ? Abstraction.NONE : regionPreserving ? Abstraction.M : Abstraction.LU;
        this.limits = limits;
        this.lower = new int[dimension];
        this.upper = new int[dimension];
    }

    Semantics semantics() {
        return semantics;
    }

    int dimension() {
        return dimension;
    }

    /** The initial state, delayed and extrapolated. */
    SymState initial() {
        SymState s = semantics.initial();
        semantics.delay(s);
        extrapolate(s);
        return s;
    }

    /** Every successor of {@code s}: a move, then delay, then extrapolation. */
    void successors(SymState s, Sink sink) {
        semantics.moves(s, (move, next) -> {
            if (semantics.delay(next)) {
                extrapolate(next);
                sink.accept(move, next);
            }
        });
    }

    /** Whether time can pass forever in {@code s}: delays allowed and no clock bounded above. */
    boolean timeDiverges(SymState s) {
        if (!semantics.mayDelay(s)) {
            return false;
        }
        Dbm z = s.zone();
        for (int i = 1; i < dimension; i++) {
            if (z.upperBound(i, 0) != Bound.INFINITY) {
                return false;
            }
        }
        return true;
    }

    /**
     * The valuations of {@code s}'s zone from which no move is possible, now or after any delay: the zone minus,
     * for every move, the valuations that can delay into its enabling set.
     */
    List<Dbm> deadlocked(SymState s) {
        List<Dbm> dead = new ArrayList<>(List.of(s.zone()));
        boolean mayDelay = semantics.mayDelay(s);
        int[] vars = vars(s);
        semantics.moves(s, (move, next) -> {
            if (dead.isEmpty()) {
                return;
            }
            Dbm enabled = enablingZone(s, vars, move, next.zone());
            if (enabled != null) {
                if (mayDelay) {
                    enabled.down();
                    enabled.intersect(s.zone());
                }
                List<Dbm> rest = Zones.subtract(dead, enabled);
                dead.clear();
                dead.addAll(rest);
            }
        });
        return dead;
    }

    /**
     * The valuations of {@code s}'s zone from which {@code move} is taken (guards hold, the target invariants hold
     * after the resets), given the zone {@code after} the move; null if none.
     */
    Dbm enablingZone(SymState s, int[] vars, Semantics.Move move, Dbm after) {
        Dbm pre = after.copy();
        for (int clock : resetClocks(vars, move)) {
            pre.free(clock);
        }
        if (!guards(s, move, pre)) {
            return null;
        }
        return pre.intersect(s.zone()) ? pre : null;
    }

    /** Intersects {@code zone} with the guards of {@code move}'s edges in {@code s}; false if it becomes empty. */
    boolean guards(SymState s, Semantics.Move move, Dbm zone) {
        int[] vars = vars(s);
        for (Semantics.Step step : move.steps()) {
            Expression guard = step.edge().guard();
            if (guard != null && !semantics.evaluator().constrain(guard, vars, step.frame(), zone, 1)) {
                return false;
            }
        }
        return !zone.isEmpty();
    }

    /** The clocks {@code move}'s updates assign, with their values: {clock, value} pairs. */
    int[][] resets(int[] vars, Semantics.Move move) {
        int[] scratch = vars.clone();
        resets.clear();
        for (Semantics.Step step : move.steps()) {
            for (Expression update : step.edge().updates()) {
                semantics.evaluator().execute(update, scratch, step.frame(), resets);
            }
        }
        int[][] out = new int[resets.size()][];
        for (int i = 0; i < out.length; i++) {
            out[i] = new int[] {resets.clock(i), resets.value(i)};
        }
        resets.clear();
        return out;
    }

    private int[] resetClocks(int[] vars, Semantics.Move move) {
        int[][] r = resets(vars, move);
        int[] clocks = new int[r.length];
        for (int i = 0; i < r.length; i++) {
            clocks[i] = r[i][0];
        }
        return clocks;
    }

    /** The integer state vector of {@code s}, as a new array. */
    int[] vars(SymState s) {
        int[] v = new int[stateSize];
        for (int i = 0; i < stateSize; i++) {
            v[i] = s.var(i);
        }
        return v;
    }

    /** Extrapolates {@code s}'s zone in place, as the successors are. */
    void extrapolate(SymState s) {
        Dbm zone = s.zone();
        if (abstraction == Abstraction.NONE) {
            return;
        }
        limits.fill(s, lower, upper);
        if (abstraction == Abstraction.LU) {
            zone.extrapolateLU(lower, upper);
        } else {
            // Extra+_M: Extra+_LU with L = U = M, within the closure of the zone under M-region equivalence
            for (int x = 1; x < dimension; x++) {
                upper[x] = Math.max(upper[x], lower[x]);
            }
            zone.extrapolateLU(upper, upper);
        }
    }
}
