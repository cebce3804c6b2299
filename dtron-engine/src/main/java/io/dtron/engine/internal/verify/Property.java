package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import java.util.ArrayList;
import java.util.List;

/**
 * A compiled state property in negation normal form: conjunctions and disjunctions of data conditions,
 * location tests, clock constraints and {@code deadlock}. {@link #restrict} gives the part of a symbolic state
 * where it holds, as a union of zones.
 */
abstract class Property {

    /** An integer expression over the state vector. */
    interface IntTerm {
        int eval(SymState s);
    }

    /** What properties need to know about a state beyond its parts: its deadlocked valuations. */
    interface StateInfo {
        /** The valuations of {@code s}'s zone from which no action is possible now or after any delay. */
        List<Dbm> deadlocked(SymState s);
    }

    /** Whether the property mentions clocks or {@code deadlock}: then it depends on the zone. */
    abstract boolean dependsOnZone();

    /** Whether the property mentions {@code deadlock}. */
    abstract boolean mentionsDeadlock();

    /**
     * Adds the property's clock bounds to {@code atoms} as {@code {clock, constant, isLower}}, for extrapolation;
     * false when one compares two clocks or has a constant that depends on the state.
     */
    boolean clockAtoms(java.util.List<int[]> atoms) {
        return true;
    }

    /** Whether the property holds in {@code s}; only for properties that do not depend on the zone. */
    abstract boolean holds(SymState s);

    /** Appends to {@code out} zones whose union is the part of {@code zone} (in state {@code s}) where it holds. */
    abstract void restrict(SymState s, Dbm zone, StateInfo info, List<Dbm> out);

    /** A property of the locations and data only: the whole zone where it holds, none where it does not. */
    abstract static class OnDiscretePart extends Property {
        @Override
        boolean dependsOnZone() {
            return false;
        }

        @Override
        boolean mentionsDeadlock() {
            return false;
        }

        @Override
        void restrict(SymState s, Dbm zone, StateInfo info, List<Dbm> out) {
            if (holds(s)) {
                out.add(zone);
            }
        }
    }

    /** {@code true} or {@code false}. */
    static final class Constant extends OnDiscretePart {
        private final boolean value;

        Constant(boolean value) {
            this.value = value;
        }

        @Override
        boolean holds(SymState s) {
            return value;
        }

        @Override
        void restrict(SymState s, Dbm zone, StateInfo info, List<Dbm> out) {
            if (value && !zone.isEmpty()) {
                out.add(zone);
            }
        }
    }

    /** A data condition: an integer expression, true when not 0 (false when {@code negated}). */
    static final class Data extends OnDiscretePart {
        private final IntTerm term;
        private final boolean negated;

        Data(IntTerm term, boolean negated) {
            this.term = term;
            this.negated = negated;
        }

        @Override
        boolean holds(SymState s) {
            return (term.eval(s) != 0) != negated;
        }
    }

    /** {@code P.loc} (or its negation). */
    static final class AtLocation extends OnDiscretePart {
        private final int process;
        private final int location;
        private final boolean negated;

        AtLocation(int process, int location, boolean negated) {
            this.process = process;
            this.location = location;
            this.negated = negated;
        }

        @Override
        boolean holds(SymState s) {
            return (s.location(process) == location) != negated;
        }
    }

    /** {@code x_i - x_j < c} or {@code x_i - x_j <= c}, c an integer expression (clock 0 is the reference). */
    static final class ClockBound extends Property {
        private final int i;
        private final int j;
        private final IntTerm constant;
        private final boolean strict;

        ClockBound(int i, int j, IntTerm constant, boolean strict) {
            this.i = i;
            this.j = j;
            this.constant = constant;
            this.strict = strict;
        }

        /** The negation: {@code x_j - x_i <= -c} for {@code <}, {@code x_j - x_i < -c} for {@code <=}. */
        ClockBound negate() {
            IntTerm c = constant;
            return new ClockBound(j, i, v -> -c.eval(v), !strict);
        }

        @Override
        boolean dependsOnZone() {
            return true;
        }

        @Override
        boolean mentionsDeadlock() {
            return false;
        }

        @Override
        boolean clockAtoms(List<int[]> atoms) {
            if (i > 0 && j > 0) {
                return false;
            }
            int c;
            try {
                c = constant.eval(null);
            } catch (NullPointerException dependsOnState) {
                return false;
            }
            atoms.add(i > 0 ? new int[] {i, Math.abs(c), 0} : new int[] {j, Math.abs(c), 1});
            return true;
        }

        @Override
        boolean holds(SymState s) {
            throw new IllegalStateException("a clock constraint depends on the zone");
        }

        @Override
        void restrict(SymState s, Dbm zone, StateInfo info, List<Dbm> out) {
            int c = constant.eval(s);
            int bound = c > Bound.MAX_VALUE ? Bound.INFINITY : c < -Bound.MAX_VALUE ? Bound.lt(-Bound.MAX_VALUE)
                    : Bound.of(c, strict);
            if (zone.upperBound(i, j) <= bound) {
                out.add(zone);
                return;
            }
            Dbm z = zone.copy();
            if (z.constrain(i, j, bound)) {
                out.add(z);
            }
        }
    }

    /** {@code deadlock}: no action now or after any delay (or, negated, some action possible). */
    static final class Deadlock extends Property {
        private final boolean negated;

        Deadlock(boolean negated) {
            this.negated = negated;
        }

        @Override
        boolean dependsOnZone() {
            return true;
        }

        @Override
        boolean mentionsDeadlock() {
            return true;
        }

        @Override
        boolean holds(SymState s) {
            throw new IllegalStateException("deadlock depends on the zone");
        }

        @Override
        void restrict(SymState s, Dbm zone, StateInfo info, List<Dbm> out) {
            List<Dbm> dead = info.deadlocked(s);
            if (!negated) {
                for (Dbm d : dead) {
                    Dbm z = d.copy();
                    if (z.intersect(zone)) {
                        out.add(z);
                    }
                }
                return;
            }
            List<Dbm> live = new ArrayList<>(List.of(zone));
            for (Dbm d : dead) {
                live = Zones.subtract(live, d);
            }
            out.addAll(live);
        }
    }

    /** A conjunction or disjunction of properties: what its parts have in common. */
    abstract static class Junction extends Property {
        final Property[] parts;
        private final boolean dependsOnZone;
        private final boolean mentionsDeadlock;

        Junction(List<Property> parts) {
            this.parts = parts.toArray(new Property[0]);
            this.dependsOnZone = parts.stream().anyMatch(Property::dependsOnZone);
            this.mentionsDeadlock = parts.stream().anyMatch(Property::mentionsDeadlock);
        }

        @Override
        boolean dependsOnZone() {
            return dependsOnZone;
        }

        @Override
        boolean mentionsDeadlock() {
            return mentionsDeadlock;
        }

        @Override
        boolean clockAtoms(List<int[]> atoms) {
            boolean all = true;
            for (Property p : parts) {
                all &= p.clockAtoms(atoms);
            }
            return all;
        }
    }

    static final class And extends Junction {
        And(List<Property> parts) {
            super(parts);
        }

        @Override
        boolean holds(SymState s) {
            for (Property p : parts) {
                if (!p.holds(s)) {
                    return false;
                }
            }
            return true;
        }

        @Override
        void restrict(SymState s, Dbm zone, StateInfo info, List<Dbm> out) {
            for (Property p : parts) {
                if (!p.dependsOnZone() && !p.holds(s)) {
                    return;
                }
            }
            List<Dbm> pieces = List.of(zone);
            for (Property p : parts) {
                if (!p.dependsOnZone()) {
                    continue;
                }
                List<Dbm> next = new ArrayList<>();
                for (Dbm piece : pieces) {
                    p.restrict(s, piece, info, next);
                }
                if (next.isEmpty()) {
                    return;
                }
                pieces = next;
            }
            out.addAll(pieces);
        }
    }

    static final class Or extends Junction {
        Or(List<Property> parts) {
            super(parts);
        }

        @Override
        boolean holds(SymState s) {
            for (Property p : parts) {
                if (p.holds(s)) {
                    return true;
                }
            }
            return false;
        }

        @Override
        void restrict(SymState s, Dbm zone, StateInfo info, List<Dbm> out) {
            for (Property p : parts) {
                if (!p.dependsOnZone() && p.holds(s)) {
                    out.add(zone);
                    return;
                }
            }
            for (Property p : parts) {
                if (p.dependsOnZone()) {
                    p.restrict(s, zone, info, out);
                }
            }
        }
    }
}
