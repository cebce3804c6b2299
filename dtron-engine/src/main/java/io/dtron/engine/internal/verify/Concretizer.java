package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import java.math.BigDecimal;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.function.Function;

/**
 * Concrete delays for a symbolic path. The path is replayed without extrapolation (exact zones), then walked
 * backwards to the zones from which the rest of the path can still be followed, then forwards choosing, at each
 * step, the earliest delay that stays in them (a point in between when the earliest is excluded). Times are
 * exact: every chosen value is an integer or a midpoint of earlier values.
 */
final class Concretizer {
    private static final BigDecimal TWO = BigDecimal.valueOf(2);

    /** A concrete step: the delay, then the clock values, then (except at the end) the move index. */
    record Step(BigDecimal delay, BigDecimal[] clocks) {
    }

    private final ZoneGraph graph;

    Concretizer(ZoneGraph graph) {
        this.graph = graph;
    }

    /**
     * The delays before each of {@code moves} and a final delay into the part of the last state that {@code
     * target} gives (from the exact last state; null for all of it); empty if the path cannot be replayed.
     */
    List<Step> concretize(List<Semantics.Move> moves, Function<SymState, Dbm> target) {
        return concretize(moves, target, null, null);
    }

    /**
     * As {@link #concretize(List, Function)}, with the valuations at the end of each state's delay kept within
     * {@code within}'s zone for that state, and those at its start within {@code entering}'s, where they have one
     * (not null): as zones are convex, a delay that starts and ends in a zone stays in it.
     */
    List<Step> concretize(List<Semantics.Move> moves, Function<SymState, Dbm> target, List<Dbm> within,
                          List<Dbm> entering) {
        Semantics sem = graph.semantics();
        int n = moves.size();
        List<SymState> before = new ArrayList<>(n + 1);
        List<Dbm> afterMove = new ArrayList<>(n + 1);
        SymState s = sem.initial();
        afterMove.add(s.zone().copy());
        sem.delay(s);
        before.add(s);
        for (Semantics.Move m : moves) {
            SymState[] found = new SymState[1];
            sem.moves(s, (move, next) -> {
                if (found[0] == null && same(move, m)) {
                    found[0] = next;
                }
            });
            if (found[0] == null) {
                return List.of();
            }
            afterMove.add(found[0].zone().copy());
            s = found[0];
            if (!sem.delay(s)) {
                return List.of();
            }
            before.add(s);
        }
        Dbm[] reach = new Dbm[n + 1];
        Dbm last = target == null ? s.zone().copy() : target.apply(s);
        if (last == null || last.isEmpty()) {
            return List.of();
        }
        if (!constrain(last, within, n)) {
            return List.of();
        }
        reach[n] = last;
        for (int i = n; i >= 1; i--) {
            Dbm x = reach[i].copy();
            if (sem.mayDelay(before.get(i))) {
                x.down();
            }
            if (!x.intersect(afterMove.get(i)) || !constrain(x, entering, i)) {
                return List.of();
            }
            SymState from = before.get(i - 1);
            int[] vars = graph.vars(from);
            for (int[] reset : graph.resets(vars, moves.get(i - 1))) {
                x.free(reset[0]);
            }
            if (!x.intersect(from.zone()) || !graph.guards(from, moves.get(i - 1), x)
                    || !constrain(x, within, i - 1)) {
                return List.of();
            }
            reach[i - 1] = x;
        }
        int dim = graph.dimension();
        BigDecimal[] v = new BigDecimal[dim];
        Arrays.fill(v, BigDecimal.ZERO);
        List<Step> out = new ArrayList<>(n + 1);
        for (int i = 0; i <= n; i++) {
            BigDecimal d = sem.mayDelay(before.get(i)) ? delayInto(v, reach[i]) : BigDecimal.ZERO;
            if (d == null) {
                return List.of();
            }
            for (int k = 1; k < dim; k++) {
                v[k] = v[k].add(d);
            }
            out.add(new Step(d, v.clone()));
            if (i < n) {
                for (int[] reset : graph.resets(graph.vars(before.get(i)), moves.get(i))) {
                    v[reset[0]] = BigDecimal.valueOf(reset[1]);
                }
            }
        }
        return out;
    }

    private static boolean constrain(Dbm zone, List<Dbm> zones, int state) {
        return zones == null || zones.get(state) == null || zone.intersect(zones.get(state));
    }

    /** The earliest delay {@code d} (or, if it is excluded, one just after) with {@code v + d} in {@code zone}. */
    private static BigDecimal delayInto(BigDecimal[] v, Dbm zone) {
        BigDecimal lo = BigDecimal.ZERO;
        boolean loStrict = false;
        BigDecimal hi = null;
        boolean hiStrict = false;
        for (int k = 1; k < v.length; k++) {
            int up = zone.upperBound(k, 0);
            if (up != Bound.INFINITY) {
                BigDecimal h = BigDecimal.valueOf(Bound.value(up)).subtract(v[k]);
                int c = hi == null ? -1 : h.compareTo(hi);
                if (c < 0 || c == 0 && Bound.isStrict(up)) {
                    hi = h;
                    hiStrict = Bound.isStrict(up);
                }
            }
            int low = zone.upperBound(0, k);
            BigDecimal l = BigDecimal.valueOf(-Bound.value(low)).subtract(v[k]);
            int c = l.compareTo(lo);
            if (c > 0 || c == 0 && Bound.isStrict(low)) {
                lo = l;
                loStrict = Bound.isStrict(low);
            }
        }
        BigDecimal d;
        if (!loStrict) {
            d = lo;
        } else if (hi == null) {
            d = lo.add(BigDecimal.ONE);
        } else {
            d = lo.add(hi).divide(TWO);
        }
        if (hi != null && (d.compareTo(hi) > 0 || hiStrict && d.compareTo(hi) == 0)) {
            return null;
        }
        return d;
    }

    /** Whether two moves take the same edges with the same select values. */
    static boolean same(Semantics.Move a, Semantics.Move b) {
        if (a.channel() != b.channel() || a.steps().size() != b.steps().size()) {
            return false;
        }
        for (int i = 0; i < a.steps().size(); i++) {
            Semantics.Step x = a.steps().get(i);
            Semantics.Step y = b.steps().get(i);
            if (x.process() != y.process() || x.edge() != y.edge() || !Arrays.equals(x.frame(), y.frame())) {
                return false;
            }
        }
        return true;
    }
}
