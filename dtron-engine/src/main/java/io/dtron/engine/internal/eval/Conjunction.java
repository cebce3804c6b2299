package io.dtron.engine.internal.eval;

import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Expression;
import io.dtron.model.Expression.Operator;
import io.dtron.xta.Pos;

/**
 * A compiled guard or invariant: its data conjuncts, evaluated first and in order, its clock atoms
 * {@code x_i - x_j ~ c} ({@code j} is the reference clock 0 for a bound on one clock), applied after all data
 * conjuncts hold, and its alternatives {@code d || g} of a data condition and a clock formula (as Uppaal allows),
 * where {@code g} applies only when {@code d} is false. A formula the engine cannot apply (a clock rate, a
 * disjunction of two clock constraints) makes every use a model error.
 */
final class Conjunction {
    private final ValueNode[] data;
    private final Atom[] atoms;
    private final Alternative[] alternatives;
    private final Expression unsupported;

    /** {@code unsupported} is the first part the engine cannot apply, or null. */
    Conjunction(ValueNode[] data, Atom[] atoms, Alternative[] alternatives, Expression unsupported) {
        this.data = data;
        this.atoms = atoms;
        this.alternatives = alternatives;
        this.unsupported = unsupported;
    }

    /** {@code condition || formula}: the formula matters only when the data condition is false. */
    record Alternative(ValueNode condition, Conjunction formula) {
        boolean dataHolds(Env env) {
            return condition.eval(env) != 0 || formula.dataHolds(env);
        }

        boolean constrain(Env env, Dbm zone, int ticksPerUnit) {
            return condition.eval(env) != 0 || formula.constrain(env, zone, ticksPerUnit);
        }

        boolean bounds(Env env, int ticksPerUnit, ClockBounds out) {
            return condition.eval(env) != 0 || formula.bounds(env, ticksPerUnit, out);
        }
    }

    /** Whether every data conjunct holds; the clock atoms are not looked at. */
    boolean dataHolds(Env env) {
        if (unsupported != null) {
            throw unsupported(unsupported);
        }
        for (ValueNode d : data) {
            if (d.eval(env) == 0) {
                return false;
            }
        }
        for (Alternative a : alternatives) {
            if (!a.dataHolds(env)) {
                return false;
            }
        }
        return true;
    }

    /** Applies the formula to {@code zone}; false when a data conjunct is false or the zone became empty. */
    boolean constrain(Env env, Dbm zone, int ticksPerUnit) {
        if (!dataHolds(env)) {
            return false;
        }
        for (Atom a : atoms) {
            if (!a.constrain(env, zone, ticksPerUnit)) {
                return false;
            }
        }
        for (Alternative a : alternatives) {
            if (!a.constrain(env, zone, ticksPerUnit)) {
                return false;
            }
        }
        return true;
    }

    /** Lists the clock bounds in {@code out}; false (and nothing listed) when a data conjunct is false. */
    boolean bounds(Env env, int ticksPerUnit, ClockBounds out) {
        if (!dataHolds(env)) {
            return false;
        }
        for (Atom a : atoms) {
            a.list(env, ticksPerUnit, out);
        }
        for (Alternative a : alternatives) {
            if (!a.bounds(env, ticksPerUnit, out)) {
                return false;
            }
        }
        return true;
    }

    /** {@code x_i - x_j ~ value} for ~ one of {@code <, <=, ==, >=, >}. */
    static final class Atom {
        private final PlaceNode i;
        private final PlaceNode j;
        private final Operator op;
        private final ValueNode value;
        private final Pos pos;

        /** {@code j} is null for a bound on clock {@code i} alone. */
        Atom(PlaceNode i, PlaceNode j, Operator op, ValueNode value, Pos pos) {
            this.i = i;
            this.j = j;
            this.op = op;
            this.value = value;
            this.pos = pos;
        }

        boolean constrain(Env env, Dbm zone, int ticksPerUnit) {
            int x = i.address(env);
            int y = j == null ? 0 : j.address(env);
            int c = scaled(value.eval(env), ticksPerUnit);
            return switch (op) {
                case LT -> zone.constrain(x, y, Bound.lt(c));
                case LE -> zone.constrain(x, y, Bound.le(c));
                case GT -> zone.constrain(y, x, Bound.lt(-c));
                case GE -> zone.constrain(y, x, Bound.le(-c));
                default -> zone.constrain(x, y, Bound.le(c)) && zone.constrain(y, x, Bound.le(-c));
            };
        }

        void list(Env env, int ticksPerUnit, ClockBounds out) {
            int x = i.address(env);
            int y = j == null ? 0 : j.address(env);
            int c = scaled(value.eval(env), ticksPerUnit);
            switch (op) {
                case LT -> out.add(x, y, Bound.lt(c));
                case LE -> out.add(x, y, Bound.le(c));
                case GT -> out.add(y, x, Bound.lt(-c));
                case GE -> out.add(y, x, Bound.le(-c));
                default -> {
                    out.add(x, y, Bound.le(c));
                    out.add(y, x, Bound.le(-c));
                }
            }
        }

        private int scaled(int c, int ticksPerUnit) {
            long ticks = (long) c * ticksPerUnit;
            if (ticks > Bound.MAX_VALUE || ticks < -Bound.MAX_VALUE) {
                throw new ModelRuntimeException(pos, "the clock bound " + c + " in '" + pos.text()
                        + "' is too large for the engine's time resolution (at most " + Bound.MAX_VALUE / ticksPerUnit
                        + " time units)");
            }
            return (int) ticks;
        }
    }

    /** The error for a formula that is not a conjunction of clock bounds and data conditions. */
    private static ModelRuntimeException unsupported(Expression e) {
        if (e instanceof Expression.ClockRate) {
            return new ModelRuntimeException(e.pos(), "clock rates such as '" + e.pos().text()
                    + "' (stopwatches) are not supported by DTRON's engine");
        }
        return new ModelRuntimeException(e.pos(), "'" + e.pos().text() + "' is not supported in a guard or an"
                + " invariant: only conjunctions of data conditions and clock bounds (x ~ c, x - y ~ c with ~ one of"
                + " <, <=, ==, >=, >) are");
    }
}
