package io.dtron.engine;

/** How the tester chooses among the inputs and delays the environment model allows. */
public enum Strategy {
    /** At random, by the {@link DelayPolicy} (the default, as Uppaal TRON). */
    RANDOM,
    /**
     * Toward the edges of the model not yet covered on an input or output, its traps not yet set and the open goals:
     * the move that starts the fewest moves covering them all (when they are a dozen or fewer before the run), else
     * the one that brings them nearest in sum, by distance in the zone graph of the closed network.
     */
    COVERAGE,
    /** Toward the nearest goal not yet reached, by distance in the zone graph of the closed network. */
    GOAL
}
