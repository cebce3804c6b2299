package io.dtron.engine.verify;

/** The order in which the reachability search explores the waiting list. */
public enum SearchOrder {
    /** Breadth-first: shortest diagnostic traces (in moves); the default. */
    BREADTH_FIRST,
    /** Depth-first: often finds a reachable state sooner and stores less on the way. */
    DEPTH_FIRST
}
