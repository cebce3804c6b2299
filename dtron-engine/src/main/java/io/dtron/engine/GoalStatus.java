package io.dtron.engine;

/**
 * What became of one goal of a run.
 *
 * @param text   the goal as written ({@code E<> p})
 * @param state  reached, unreachable or still open
 * @param micros when it was reached or found unreachable, in microseconds since the start (-1 before the run)
 * @param reason for an unreachable goal, why; else null
 */
public record GoalStatus(String text, State state, long micros, String reason) {
    /** Where a goal stands. */
    public enum State {
        /**
         * Every state the system may be in satisfied it at {@link #micros}: after the event then, or just before it
         * (every state the event can have started from).
         */
        REACHED,
        /** No path of the model leads to it any more (or ever: {@link #micros} is -1). */
        UNREACHABLE,
        /** Neither yet. */
        OPEN
    }
}
