package io.dtron.engine.verify;

/**
 * The shortest time in which a run of a model can set every one of its traps ({@link Verifier#fastestCover}).
 *
 * @param answer   whether such a time was found, no run sets them all, or the search stopped at its state limit
 * @param units    the time, in model time units, when {@link Answer#FOUND}; else -1
 * @param strict   whether the time is an infimum that no run reaches exactly (a run sets them all just after it)
 * @param explored how many symbolic states the search explored
 */
public record CoverTime(Answer answer, long units, boolean strict, long explored) {
    /** How the search ended. */
    public enum Answer {
        /** The shortest time was found. */
        FOUND,
        /** The search explored every reachable state: no run sets every trap. */
        NONE,
        /** The search stopped at its state limit before it found one: unknown. */
        UNKNOWN
    }
}
