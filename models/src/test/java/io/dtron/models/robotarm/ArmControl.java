package io.dtron.models.robotarm;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.math.BigDecimal;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * A run of {@code dtron control} in the test's JVM against a robot arm plant in a process of its own (the Java plant
 * of {@link ArmProcess}, the Python one), in real time on a bus, and what the model guarantees of it.
 */
final class ArmControl {
    private static final Pattern ALARM = Pattern.compile("ALARM at t=([0-9.]+): no reading came by t=([0-9.]+): the"
            + " model required the plant to act by then\\. The model allowed these readings: arrived between"
            + " t=([0-9.]+) and t=([0-9.]+) \\(Arm: Moving -> Arrived\\)\\. At the last observation the plant was in"
            + " Arm\\.Moving\\.");

    private ArmControl() {
    }

    /** What the controller printed and its exit code, and the plant's output. */
    record Run(int exit, String out, String err, String plant) {
        String shown() {
            return "exit " + exit + "\n" + out + err + "\nplant:\n" + plant;
        }
    }

    /**
     * Runs {@code dtron control} with {@code controlArgs} against {@code plant}, started with its output to {@code
     * log}; the plant must exit after its run. The plant is stopped when this returns.
     */
    static Run control(Process plant, Path log, List<String> controlArgs) throws Exception {
        try {
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            int exit = DtronCommand.run(controlArgs.toArray(String[]::new), new PrintWriter(out, true),
                    new PrintWriter(err, true));
            boolean exited = plant.waitFor(30, TimeUnit.SECONDS);
            Run run = new Run(exit, out.toString(), err.toString(), Files.readString(log));
            assertTrue(exited, "the plant exits after its run: " + run.shown());
            return run;
        } finally {
            plant.destroyForcibly();
        }
    }

    /**
     * The correct arm was controlled for the whole run of 40 units: no alarm, the plant never got the safe action
     * and every command came in a state that takes it.
     */
    static void assertControlledWithoutAlarm(Run run) {
        assertEquals(0, run.exit(), run.shown());
        assertTrue(run.out().contains("in real time"), run.shown());
        assertTrue(run.out().lines().anyMatch(l -> l.startsWith("control COMPLETED at t=40.000: ")
                && l.contains(" 0 alarms")), run.shown());
        assertFalse(run.out().contains("ALARM"), run.shown());
        assertFalse(run.plant().contains("stopped at"), "no safe action was sent: " + run.shown());
        assertFalse(run.plant().contains("ignored"), "every command came in a state that takes it: " + run.shown());
    }

    /**
     * The stalling arm raised the alarm once the model's deadline, 5 units after the move, had passed, naming the
     * missing reading, and received the safe action, stop.
     */
    static void assertStoppedAfterTheDeadline(Run run) {
        assertEquals(2, run.exit(), run.shown());
        Matcher alarm = ALARM.matcher(run.out());
        assertTrue(alarm.find(), run.shown());
        BigDecimal at = new BigDecimal(alarm.group(1));
        BigDecimal deadline = new BigDecimal(alarm.group(2));
        BigDecimal earliest = new BigDecimal(alarm.group(3));
        assertEquals(deadline, new BigDecimal(alarm.group(4)), run.shown());
        // the window 2 to 5 units after the move: the deadline is the model's bound, MOVE_MAX after the move; the
        // controller keeps the move in the tick interval it was sent in (a thousandth of a unit), so that a move sent
        // between two ticks widens the window by that tick
        BigDecimal width = deadline.subtract(earliest);
        assertTrue(width.compareTo(new BigDecimal("3.000")) >= 0 && width.compareTo(new BigDecimal("3.001")) <= 0,
                run.shown());
        assertTrue(at.compareTo(deadline) > 0, "no alarm before the deadline has passed: " + run.shown());
        assertTrue(run.out().contains("safe action stop() sent at t=" + alarm.group(1)), run.shown());
        // the run ends once the safe action is published, a moment after the alarm in real time
        assertTrue(run.out().lines().anyMatch(l -> l.startsWith("control ALARM at t=") && l.contains(": 2"
                + " commands sent, 0 readings, 1 alarm, safe action stop() taken")), run.shown());
        assertTrue(run.plant().contains("stopped at t="), "the plant received stop: " + run.shown());
    }
}
