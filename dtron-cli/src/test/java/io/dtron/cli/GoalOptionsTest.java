package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** dtron run's goals and strategies on the bundled ticker, in virtual time: the goals file, and bad options. */
class GoalOptionsTest {
    private static final String TICKER = Path.of("..", "models", "src", "main", "resources", "io", "dtron", "models",
            "ticker.xml").toString();

    @TempDir
    Path dir;

    private static CommandRun run(String... more) {
        List<String> args = new ArrayList<>(List.of("run", TICKER, "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "1", "--timeout", "500"));
        args.addAll(List.of(more));
        return CommandRun.of(args.toArray(String[]::new));
    }

    @Test
    void goalsFromAQueryFileAreReachedAndSaidWhen() throws Exception {
        Path q = dir.resolve("goals.q");
        Files.writeString(q, "// the third tick\nE<> o_tick_seq == 3\n");
        CommandRun r = run("--strategy", "goal", "--goals", q.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("PASSED: every goal was reached: 'E<> o_tick_seq == 3'\n"), r.out());
        assertTrue(r.out().contains("goal 'E<> o_tick_seq == 3': reached at t=30.000\n"), r.out());
    }

    @Test
    void aGoalOutOfTheVariablesRangeIsSaidUnreachableBeforeTheRun() {
        CommandRun r = run("--goal", "E<> o_tick_seq > 999");
        assertEquals(3, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("dtron run: goal 'E<> o_tick_seq > 999' is unreachable: the model checker finds no"
                + " reachable state where it holds"), r.out());
        assertTrue(r.out().contains("statistics: 1 INCONCLUSIVE 0 0 0 "), r.out());
    }

    @Test
    void badOptionsAreOneLineErrors() throws Exception {
        assertEquals("dtron run: unknown strategy 'fast' (use random, coverage or goal)", firstLine(run("--strategy",
                "fast")));
        assertEquals("dtron run: --strategy goal needs a goal: give --goal 'E<> P' or --goals FILE.q",
                firstLine(run("--strategy", "goal")));
        assertEquals("dtron run: --goal: goal 'A[] o_tick_seq < 1000' is not a reachability query: a goal is written"
                + " E<> p", firstLine(run("--goal", "A[] o_tick_seq < 1000")));
        assertEquals("dtron run: --horizon must be at least 1 move: 0", firstLine(run("--strategy", "coverage",
                "--horizon", "0")));
        Path q = dir.resolve("bad.q");
        Files.writeString(q, "E<> o_tick_seq ==\n");
        assertTrue(firstLine(run("--goals", q.toString())).startsWith("dtron run: --goals " + q + ": line 1"),
                run("--goals", q.toString()).err());
    }

    @Test
    void verifyTrapsOnAModelWithoutTrapsSaysSo() {
        CommandRun r = CommandRun.of("verify", TICKER, "--traps");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertEquals("dtron verify: " + TICKER + " has no traps: bool variables or arrays whose name starts with trap"
                + " or t_", r.err().strip());
    }

    private static String firstLine(CommandRun r) {
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(!r.err().contains("\tat "), r.err());
        return r.err().lines().findFirst().orElse("");
    }
}
