package io.dtron.engine.sim;

import io.dtron.model.Network;

/**
 * A mutant of a model's implementation part: the model with one small change, to be run as the system under test
 * ({@link ModelSystem}) against the model as specification.
 *
 * @param number     its number, from 1, in the order {@link Mutants#derive} made them
 * @param kind       the kind of change
 * @param process    the process changed
 * @param change     what changed, as text ({@code x <= 5 -> x <= 6})
 * @param where      where, as {@code file:line}
 * @param network    the mutated model; null when it could not be built
 * @param invalid    why the mutant cannot be built or run (the engine refuses it), or null
 * @param equivalent why no test can tell it from the model (what the checker proved), or null
 */
public record Mutant(int number, Kind kind, String process, String change, String where, Network network,
                     String invalid, String equivalent) {

    /** The kinds of change. */
    public enum Kind {
        /** A bound of a guard moved by one (up or down). */
        GUARD_BOUND("guard bound"),
        /** A bound of a location invariant moved by one (up or down). */
        INVARIANT_BOUND("invariant bound"),
        /** An output edge made never enabled. */
        OUTPUT_DROPPED("output dropped"),
        /** An output edge's clock bounds (guard and source invariant) all one time unit earlier. */
        OUTPUT_EARLY("output early"),
        /** An output edge's clock bounds (guard and source invariant) all one time unit later. */
        OUTPUT_LATE("output late"),
        /** A wrong value assigned to a variable attached to the output of the edge. */
        OUTPUT_VALUE("output value"),
        /** An urgent or committed location made ordinary. */
        URGENCY_REMOVED("urgency removed");

        private final String label;

        Kind(String label) {
            this.label = label;
        }

        /** The kind as people read it ({@code guard bound}). */
        public String label() {
            return label;
        }
    }
}
