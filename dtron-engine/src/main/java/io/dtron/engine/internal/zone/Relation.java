package io.dtron.engine.internal.zone;

/** How the set of valuations of one zone relates to that of another; see {@link Dbm#relation}. */
public enum Relation {
    /** Both zones hold the same valuations (two empty zones are equal). */
    EQUAL,
    /** The first zone is strictly contained in the second. */
    SUBSET,
    /** The first zone strictly contains the second. */
    SUPERSET,
    /** Neither zone contains the other. */
    DIFFERENT
}
