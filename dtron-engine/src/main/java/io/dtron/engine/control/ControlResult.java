package io.dtron.engine.control;

import java.util.List;
import java.util.Objects;

/**
 * How a control run ended.
 *
 * @param outcome     how it ended
 * @param reason      why (the alarm, or what stopped it), or null when it ran its duration
 * @param seed        the seed of its choices
 * @param commands    commands sent (the safe action included)
 * @param readings    readings the model allowed
 * @param alarms      alarms raised (0 or 1: the run ends at the first)
 * @param alarmMicros when the alarm was raised, or -1
 * @param safeAction  the safe action taken after the alarm (its command, as {@code stop} or {@code stop(v=1)}), or
 *                    null
 * @param versions    the model versions taken during the run, each as {@code LABEL at t=UNITS}
 * @param refused     the model versions refused, each as {@code LABEL: REASON}
 * @param durationMicros how long the run lasted
 */
public record ControlResult(Outcome outcome, String reason, long seed, int commands, int readings, int alarms,
                            long alarmMicros, String safeAction, List<String> versions, List<String> refused,
                            long durationMicros) {

    /** How a control run ended. */
    public enum Outcome {
        /** It ran its duration, the plant as the model allows. */
        COMPLETED,
        /** The plant deviated from the model: an alarm (and the safe action, if the model has one). */
        ALARM,
        /** It could not go on for another reason (a model error, the plant lost, the controller held up). */
        STOPPED
    }

    public ControlResult {
        Objects.requireNonNull(outcome, "outcome");
        versions = List.copyOf(versions);
        refused = List.copyOf(refused);
    }

    /** {@code micros} as a run time in model time units with three decimals, {@code t=5.001}. */
    public static String time(long micros, long unitMicros) {
        return "t=" + io.dtron.engine.internal.tester.Plan.units(micros, unitMicros);
    }

    /** The one-line summary: outcome, time, commands, readings, alarms, versions, in model time units. */
    public String summary(long unitMicros) {
        return "control " + outcome + " at " + time(durationMicros, unitMicros)
                + ": " + commands + " command" + (commands == 1 ? "" : "s") + " sent, " + readings + " reading"
                + (readings == 1 ? "" : "s") + ", " + alarms + " alarm" + (alarms == 1 ? "" : "s")
                + (safeAction == null ? "" : ", safe action " + safeAction + " taken")
                + (versions.isEmpty() ? "" : ", " + versions.size() + " model version" + (versions.size() == 1 ? ""
                : "s") + " taken") + (refused.isEmpty() ? "" : ", " + refused.size() + " refused") + " (seed " + seed
                + ")";
    }
}
