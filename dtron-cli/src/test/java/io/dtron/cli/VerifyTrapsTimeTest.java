package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The last line but one of {@code dtron verify --traps}: the shortest time in which a run sets every trap, worked out
 * by hand on small models (the goals page shows the found and the unreachable case).
 */
class VerifyTrapsTimeTest {

    private static CommandRun verify(Path dir, String model) throws Exception {
        Path file = dir.resolve("m.xta");
        Files.writeString(file, model);
        return CommandRun.of("verify", file.toString(), "--traps", "--trace", "none");
    }

    private static String lineBeforeLast(CommandRun r) {
        var lines = r.out().lines().toList();
        return lines.get(lines.size() - 2);
    }

    /** Each trap can be set, never both: one branch each, and no way back. */
    @Test
    void trapsThatNoRunSetsTogether(@TempDir Path dir) throws Exception {
        CommandRun r = verify(dir, """
                bool t_a, t_b;
                process P() {
                    clock x;
                    state S, A, B;
                    init S;
                    trans S -> A { guard x >= 1; assign t_a = true; },
                          S -> B { guard x >= 1; assign t_b = true; };
                }
                system P;
                """);
        assertEquals(2, r.exit(), r.out() + r.err()); // E<> t_a and t_b does not hold
        assertTrue(lineBeforeLast(r).matches("no run sets every trap \\(\\d+ symbolic states explored\\)"),
                lineBeforeLast(r));
    }

    /** t_a at 2, then t_b more than 4 later: any time after 6, never at 6 itself. */
    @Test
    void aStrictBoundIsJustOver(@TempDir Path dir) throws Exception {
        CommandRun r = verify(dir, """
                bool t_a, t_b;
                process P() {
                    clock x;
                    state S0, S1, S2;
                    init S0;
                    trans S0 -> S1 { guard x >= 2; assign t_a = true, x = 0; },
                          S1 -> S2 { guard x > 4; assign t_b = true; };
                }
                system P;
                """);
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(lineBeforeLast(r).matches(
                "the shortest time to set every trap: just over 6 time units \\(\\d+ symbolic states explored\\)"),
                lineBeforeLast(r));
    }
}
