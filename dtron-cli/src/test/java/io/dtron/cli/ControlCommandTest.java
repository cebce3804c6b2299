package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron control}'s usage errors on the robot-arm sample: each one line naming what is wrong, exit code 1, no
 * stack trace; a bus with no plant on it is one line too.
 */
class ControlCommandTest {
    static final String ARM = Path.of("../models/src/main/resources/io/dtron/models/robotarm/robot-arm.xta")
            .toString();

    private static void refused(String expected, String... options) {
        String[] args = new String[options.length + 2];
        args[0] = "control";
        args[1] = ARM;
        System.arraycopy(options, 0, args, 2, options.length);
        CommandRun r = CommandRun.of(args);
        assertEquals(1, r.exit(), r.out() + r.err());
        assertFalse(r.err().contains("\tat "), r.err());
        assertTrue(r.err().startsWith("dtron control: " + expected), r.err());
    }

    @Test
    void badOptionsAreOneLineErrors() {
        refused("the plant is on the bus (--cluster, --bus): leave out --plant", "--plant", "model", "--duration", "10",
                "--cluster", "arm");
        refused("a plant on the bus runs in real time: leave out --virtual-time", "--duration", "10",
                "--virtual-time", "--cluster", "arm");
        refused("name the plant: --plant model (the model's own plant part), or a bus", "--duration", "10",
                "--virtual-time");
        refused("--wait-timeout, --key-file, --insecure and --reload-from-bus are for a plant on the bus", "--plant", "model",
                "--duration", "10", "--virtual-time", "--wait-timeout", "5");
        refused("--wait-timeout, --key-file, --insecure and --reload-from-bus are for a plant on the bus", "--plant", "model",
                "--duration", "10", "--virtual-time", "--insecure");
        refused("--wait-timeout, --key-file, --insecure and --reload-from-bus are for a plant on the bus",
                "--plant", "model", "--duration", "10", "--virtual-time", "--reload-from-bus");
        refused("--reload-from-bus takes model versions only from a bus with a secret: leave out --insecure",
                "--cluster", "arm", "--duration", "10", "--insecure", "--reload-from-bus");
        refused("--insecure uses no secret: leave out --key-file", "--cluster", "arm", "--duration", "10",
                "--insecure", "--key-file", "bus.key");
        refused("--wait-timeout must be a positive number of seconds", "--cluster", "arm", "--duration", "10",
                "--wait-timeout", "0");
        refused("--plant must be 'model'", "--plant", "python", "--duration", "10", "--virtual-time");
        refused("--plant model runs in virtual time: add --virtual-time", "--plant", "model", "--duration", "10");
        refused("--duration must be a positive number of time units: 0", "--plant", "model", "--duration", "0",
                "--virtual-time");
        refused("--policy must be eager, random or goal: lazy", "--plant", "model", "--duration", "10",
                "--virtual-time", "--policy", "lazy");
        refused("the goal policy needs at least one goal (E<> p)", "--plant", "model", "--duration", "10",
                "--virtual-time", "--policy", "goal");
        refused("the safe action i_halt is no input (command) of the model; its inputs are [i_move, i_grip, i_release,"
                + " i_stop]", "--plant", "model", "--duration", "10", "--virtual-time", "--safe-action", "i_halt");
        refused("the safe location Arm.Stopped must be entered by edges that send one command, the safe action; no edge"
                + " into it sends a command", "--plant", "model", "--duration", "10", "--virtual-time",
                "--safe-location", "Arm.Stopped");
        refused("the safe location Robot.Safe: the model has no process Robot", "--plant", "model", "--duration", "10",
                "--virtual-time", "--safe-location", "Robot.Safe");
        refused("give --safe-action or --safe-location, not both", "--plant", "model", "--duration", "10",
                "--virtual-time", "--safe-action", "i_stop", "--safe-location", "Controller.Safe");
        refused("--plant-mutant 99: the plant part has mutants 1 to 14", "--plant", "model", "--duration", "10",
                "--virtual-time", "--plant-mutant", "99");
        refused("--reload-from /no/such/folder/v2.xta: its folder does not exist", "--plant", "model", "--duration",
                "10", "--virtual-time", "--reload-from", "/no/such/folder/v2.xta");
        refused("--reload-from /tmp: give the file new versions are written to, not a folder", "--plant", "model",
                "--duration", "10", "--virtual-time", "--reload-from", "/tmp");
    }

    @Test
    void aVersionFileNotThereYetIsSaidAndTheRunGoesOn(@TempDir Path dir) {
        Path later = dir.resolve("later.xta");
        CommandRun r = CommandRun.of("control", ARM, "--plant", "model", "--duration", "100", "--virtual-time",
                "--seed", "1", "--reload-from", later.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("dtron control: --reload-from " + later + ": no such file yet; a version written"
                + " there is checked when it appears\n"), r.out());
    }

    @Test
    void aBusWithoutThePlantIsOneLineAfterTheWarningOfWindowsTooNarrow() {
        // the embedded JGroups bus on loopback, a name of its own: no member serves the arm's channels; at 1 ms a time
        // unit the arm's release window (1 unit) is narrower than the 2 ms margin commands get at least
        String cluster = "no-arm-" + ProcessHandle.current().pid();
        CommandRun r = CommandRun.of("control", ARM, "--cluster", cluster, "--duration", "10", "--timeunit", "1000",
                "--wait-timeout", "1");
        assertEquals(1, r.exit(), r.out() + r.err());
        List<String> lines = r.err().strip().lines().toList();
        assertEquals(2, lines.size(), r.err());
        assertTrue(lines.get(0).startsWith("dtron control: warning: the window of input i_release in Controller (3 <="
                + " c <= 4, "), r.err());
        assertTrue(lines.get(0).endsWith("inputs in such a window are aimed at its start and may still come late (the"
                + " controller then stops: the command's window had closed)"), r.err());
        assertTrue(lines.get(1).startsWith("dtron control: bus '" + cluster + "' at 127.0.0.1: within 1 s no member"
                + " on the bus served input grip, input move, input release, input stop, output arrived, output"
                + " gripped"), r.err());
    }

    @Test
    void aVersionThatDoesNotLoadIsRefusedCountedAndTheRunGoesOn(@TempDir Path dir) throws Exception {
        Path broken = Files.writeString(dir.resolve("next.xta"), "chan i_move;;\n");
        CommandRun r = CommandRun.of("control", ARM, "--plant", "model", "--duration", "100", "--virtual-time",
                "--seed", "1", "--reload-from", broken.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("\nmodel version " + broken + " refused: it does not load: " + broken
                + ":1:13: error: syntax error"), r.out());
        assertTrue(r.out().endsWith(", 0 alarms, 1 refused (seed 1)\n"), r.out());
    }

    @Test
    void theSafeLocationSendsItsCommand() {
        CommandRun r = CommandRun.of("control", ARM, "--plant", "model", "--plant-mutant", "7", "--duration", "100",
                "--virtual-time", "--seed", "3", "--safe-location", "Controller.Safe");
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("\nsafe action stop() sent at t="), r.out());
    }
}
