package io.dtron.engine.internal.sem;

import io.dtron.engine.internal.zone.Dbm;
import java.util.Arrays;

/**
 * A symbolic state of the network: each process's location, the integer state vector and a zone over the
 * clocks (plus, as the last clock, the tester's clock of time elapsed since the last observation).
 */
public final class SymState {
    final int[] locations;
    final int[] vars;
    final Dbm zone;
    private final int discreteHash;

    SymState(int[] locations, int[] vars, Dbm zone) {
        this(locations, vars, zone, 31 * Arrays.hashCode(locations) + Arrays.hashCode(vars));
    }

    SymState(int[] locations, int[] vars, Dbm zone, int discreteHash) {
        this.locations = locations;
        this.vars = vars;
        this.zone = zone;
        this.discreteHash = discreteHash;
    }

    /**
     * A state with these locations (-1 leaves a process out: it takes part in no move and its invariants do not
     * apply), variables and zone, all owned by the state from now on.
     */
    public static SymState of(int[] locations, int[] vars, Dbm zone) {
        return new SymState(locations, vars, zone);
    }

    /** The location of process {@code p} (-1 for a process without locations). */
    public int location(int p) {
        return locations[p];
    }

    /** The locations, one per process (not a copy; do not change it). */
    public int[] locations() {
        return locations;
    }

    /** The integer state vector (not a copy; do not change it). */
    public int[] vars() {
        return vars;
    }

    /** The value of slot {@code slot} of the integer state vector. */
    public int var(int slot) {
        return vars[slot];
    }

    /** The zone (not a copy; do not change it). */
    public Dbm zone() {
        return zone;
    }

    /** A state with the same discrete part and a copy of the zone. */
    public SymState copy() {
        return new SymState(locations, vars, zone.copy(), discreteHash);
    }

    /** A state with the same discrete part (shared, not copied) and {@code zone}. */
    public SymState withZone(Dbm zone) {
        return new SymState(locations, vars, zone, discreteHash);
    }

    /** Whether the discrete parts (locations and variables) are equal. */
    public boolean sameDiscrete(SymState o) {
        return discreteHash == o.discreteHash && Arrays.equals(locations, o.locations) && Arrays.equals(vars, o.vars);
    }

    /** A hash of the discrete part, equal for states with {@link #sameDiscrete the same discrete part}. */
    public int discreteHash() {
        return discreteHash;
    }

    @Override
    public String toString() {
        return Arrays.toString(locations) + " " + Arrays.toString(vars) + " " + zone;
    }
}
