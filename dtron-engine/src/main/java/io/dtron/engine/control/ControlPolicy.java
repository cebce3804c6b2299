package io.dtron.engine.control;

/** How the controller chooses its next command and its time among those its model allows. */
public enum ControlPolicy {
    /** Each command as early as the model allows it (among several at once, one at random). */
    EAGER,
    /** A command and its time at random in the windows the model allows, as the tester's random delay policy. */
    RANDOM,
    /** Toward the goals ({@code E<> p}) not yet reached, with the planner of {@code --strategy goal}. */
    GOAL
}
