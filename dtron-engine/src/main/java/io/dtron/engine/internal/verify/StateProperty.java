package io.dtron.engine.internal.verify;

import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import io.dtron.model.Network;
import java.util.ArrayList;
import java.util.List;

/** The state property of an {@code E<>} query, applied to the online tester's states (zones of ticks). */
public final class StateProperty {
    private final Property property;

    private StateProperty(Property property) {
        this.property = property;
    }

    /**
     * Compiles the property of goal {@code query} for zones of {@code ticksPerUnit} ticks per model time unit.
     *
     * @throws QueryException when the goal is not an {@code E<>} query, mentions {@code deadlock}, or does not
     *                        compile
     */
    public static StateProperty goal(Network network, Query query, int ticksPerUnit) {
        Property p = DiscreteGraph.compile(new PropertyCompiler(network, ticksPerUnit), query);
        if (p.mentionsDeadlock()) {
            throw new QueryException("goal '" + query.text() + "': a run cannot tell a deadlock, so a goal cannot"
                    + " mention it");
        }
        return new StateProperty(p);
    }

    /** Whether the property mentions clocks: then it may come to hold while time passes. */
    public boolean dependsOnZone() {
        return property.dependsOnZone();
    }

    /** Whether the property holds for some valuation of {@code s}'s zone. */
    public boolean holdsSomewhere(SymState s) {
        if (!property.dependsOnZone()) {
            return property.holds(s);
        }
        List<io.dtron.engine.internal.zone.Dbm> parts = new ArrayList<>(1);
        property.restrict(s, s.zone(), x -> List.of(), parts);
        return !parts.isEmpty();
    }
}
