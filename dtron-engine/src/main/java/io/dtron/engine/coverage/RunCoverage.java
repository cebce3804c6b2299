package io.dtron.engine.coverage;

/**
 * The coverage of a run in progress, as the tester has recorded it so far (the events it has committed to): read
 * on the tester's thread (by a strategy choosing inputs, a stop condition), or after the run. Processes, locations
 * and edges are numbered as in the model's {@link io.dtron.model.Network} ({@code Process#index}, {@code
 * Location#index}, {@code Edge#index}); traps as in {@link #trapNames()}.
 *
 * <p>An edge or location counts as covered when it was taken or visited <em>for certain</em>: by every state the
 * tester kept after an observation. One that only some of them took is {@linkplain #edgePossiblyTaken possibly}
 * taken and does not count.
 */
public interface RunCoverage {

    /** Whether edge {@code edge} of process {@code process} was taken for certain. */
    boolean edgeTaken(int process, int edge);

    /** Whether edge {@code edge} of process {@code process} was taken by some state of the set (certain or not). */
    boolean edgePossiblyTaken(int process, int edge);

    /** Whether location {@code location} of process {@code process} was visited for certain. */
    boolean locationVisited(int process, int location);

    /**
     * Whether the model checker left edge {@code edge} of {@code process} in what can be covered: it is reachable,
     * or the check ran out of its budget before it could say.
     */
    boolean edgeCoverable(int process, int edge);

    /** Whether location {@code location} of {@code process} is in what can be covered (as for edges). */
    boolean locationCoverable(int process, int location);

    /** The traps' names ({@code t[2]}, {@code trapLow}), in state-vector order. */
    java.util.List<String> trapNames();

    /** Whether trap number {@code trap} (an index of {@link #trapNames()}) is set for certain. */
    boolean trapSet(int trap);

    /** Covered and coverable edges, environment and implementation together. */
    Coverage.Figure edges();

    /** Covered and coverable locations. */
    Coverage.Figure locations();

    /** Traps set and traps. */
    Coverage.Figure traps();

    /** An immutable copy of what has been covered so far. */
    Coverage snapshot();
}
