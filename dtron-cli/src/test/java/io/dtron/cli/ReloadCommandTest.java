package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import org.junit.jupiter.api.Test;

/**
 * {@code dtron reload}: its usage errors are one line with exit code 1, and a version no controller answers (a bus of
 * its own, nobody on it) is one line with exit code 3 after the wait.
 */
class ReloadCommandTest {
    private static final String V2 = Path.of("../models/src/main/resources/io/dtron/models/robotarm/robot-arm-v2.xta")
            .toString();

    @Test
    void badOptionsAreOneLineErrors() {
        CommandRun r = CommandRun.of("reload", V2, "--cluster", "arm", "--wait-timeout", "0");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.err().startsWith("dtron reload: --wait-timeout must be a positive number of seconds"), r.err());
        r = CommandRun.of("reload", "/no/such/v2.xta", "--cluster", "arm");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.err().startsWith("dtron reload: cannot read /no/such/v2.xta"), r.err());
        assertFalse(r.err().contains("\tat "), r.err());
    }

    @Test
    void aVersionNoControllerAnswersIsOneLineAfterTheWait() {
        String cluster = "no-controller-" + ProcessHandle.current().pid();
        CommandRun r = CommandRun.of("reload", V2, "--cluster", cluster, "--wait-timeout", "1");
        assertEquals(3, r.exit(), r.out() + r.err());
        assertTrue(r.out().startsWith("dtron reload: " + V2 + " sent on bus '" + cluster + "' as version "), r.out());
        assertEquals("dtron reload: within 1 s no controller on bus '" + cluster + "' took or refused version "
                + r.out().strip().replaceAll(".* as version ", "") + " (is it running with --reload-from-bus?)\n",
                r.err());
    }
}
