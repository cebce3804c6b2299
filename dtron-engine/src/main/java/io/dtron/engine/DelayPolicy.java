package io.dtron.engine;

/** How the tester chooses the time of an input within the window the environment model allows. */
public enum DelayPolicy {
    /** Uniformly at random in the window (the default). */
    RANDOM,
    /** As early as possible. */
    EAGER,
    /** As late as possible. */
    LAZY,
    /** Uniformly at random, but at most the bound after the window opens. */
    RANDOM_BOUNDED
}
