package io.dtron.engine.control;

import io.dtron.engine.Event;

/** Follows a control run; called on the controller's thread. Times are microseconds since the run's start. */
public interface ControlListener {
    /** The controller published {@code command}. */
    default void commandSent(Event command, long micros) {
    }

    /** The plant's reading {@code reading} came and the model allowed it. */
    default void readingTaken(Event reading, long micros) {
    }

    /** The plant deviated from the model: {@code reason} says how. */
    default void alarm(String reason, long micros) {
    }

    /** The controller took the safe action {@code command} after an alarm. */
    default void safeActionTaken(Event command, long micros) {
    }

    /** The controller runs model version {@code version} from now on (it was taken at a reset point). */
    default void versionTaken(String version, long micros) {
    }

    /** Model version {@code version} was refused, for {@code reason}; the run goes on with the one it has. */
    default void versionRefused(String version, String reason) {
    }
}
