package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import java.util.ArrayList;
import java.util.List;

/** Unions of zones, as lists of zones: what {@code deadlock} and its negation need. */
final class Zones {
    private Zones() {
    }

    /** The valuations of {@code zones} that are not in {@code minus}, as disjoint pieces of each zone. */
    static List<Dbm> subtract(List<Dbm> zones, Dbm minus) {
        if (minus.isEmpty()) {
            return zones;
        }
        List<Dbm> out = new ArrayList<>();
        int dim = minus.dimension();
        for (Dbm z : zones) {
            if (z.isSubsetOf(minus)) {
                continue;
            }
            Dbm rest = z.copy();
            if (!rest.intersect(minus)) {
                out.add(z);
                continue;
            }
            // z minus D: for each constraint c of D, the part of z (within the earlier constraints) violating c
            Dbm inside = z.copy();
            for (int i = 0; i < dim; i++) {
                for (int j = 0; j < dim; j++) {
                    int b = minus.upperBound(i, j);
                    if (i == j || b == Bound.INFINITY || inside.upperBound(i, j) <= b) {
                        continue;
                    }
                    Dbm outside = inside.copy();
                    if (outside.constrain(j, i, negate(b))) {
                        out.add(outside);
                    }
                    if (!inside.constrain(i, j, b)) {
                        break;
                    }
                }
            }
        }
        return out;
    }

    /** The bound on {@code x_j - x_i} that holds exactly when {@code x_i - x_j} violates {@code b}. */
    static int negate(int b) {
        return Bound.of(-Bound.value(b), !Bound.isStrict(b));
    }
}
