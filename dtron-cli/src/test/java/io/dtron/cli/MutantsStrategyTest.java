package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron mutants --strategy coverage} steers every run, in virtual time: on a combination lock that opens
 * after ten presses of {@code a} in a row (a press of {@code b} starts again), only a steered run gets far enough,
 * within a budget of 50 time units, to see what a mutant of the opening does wrong.
 */
class MutantsStrategyTest {
    /** The lock: the user presses at most once a time unit; the lock says open within a unit of the tenth a. */
    static final String LOCK = """
            chan i_a, i_b, o_open;
            int[0,9] n;

            process Lock() {
                clock x;
                state Closed, Opening { x <= 1 };
                init Closed;
                trans Closed -> Closed { guard n < 9; sync i_a?; assign n = n + 1; },
                      Closed -> Opening { guard n == 9; sync i_a?; assign n = 0, x = 0; },
                      Closed -> Closed { sync i_b?; assign n = 0; },
                      Opening -> Closed { sync o_open!; };
            }

            process User() {
                clock y;
                state Idle;
                init Idle;
                trans Idle -> Idle { guard y >= 1; sync i_a!; assign y = 0; },
                      Idle -> Idle { guard y >= 1; sync i_b!; assign y = 0; },
                      Idle -> Idle { sync o_open?; };
            }

            system Lock, User;
            """;

    @Test
    void onlyTheSteeredRunsReachTheOpeningAndKillItsMutants(@TempDir Path dir) throws Exception {
        Path model = dir.resolve("lock.xta");
        Files.writeString(model, LOCK);
        Map<?, ?> random = mutants(dir, model, "random", "1");
        Map<?, ?> coverage = mutants(dir, model, "coverage", "1");
        assertEquals("random", random.get("strategy"));
        assertEquals("coverage", coverage.get("strategy"));
        assertEquals(0L, random.get("killed"), "no random run presses a ten times in a row within 50 units");
        assertEquals(3L, random.get("model_runs_passed"));
        assertEquals(3L, coverage.get("model_runs_passed"));
        assertTrue((Long) coverage.get("killed") > 0, coverage.toString());
        Map<?, ?> dropped = mutant(coverage, "output dropped");
        assertEquals("killed", dropped.get("status"), dropped.toString());
        assertEquals(1L, dropped.get("seed"), "the first steered run kills it");
        assertEquals("survived", mutant(random, "output dropped").get("status"));
        assertEquals(statuses(coverage), statuses(mutants(dir, model, "coverage", "2")),
                "the same on 1 thread and on 2: each run depends on its seed alone");
    }

    @Test
    void theFirstLineSaysTheStrategy(@TempDir Path dir) throws Exception {
        Path model = dir.resolve("lock.xta");
        Files.writeString(model, LOCK);
        CommandRun r = CommandRun.of("mutants", model.toString(), "--budget", "50", "--seeds", "1", "--seed", "1",
                "--threads", "1", "--strategy", "coverage");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().lines().findFirst().orElseThrow().endsWith(", delay policy random, strategy coverage"),
                r.out());
    }

    @Test
    void aGoalThatDoesNotCompileIsAUsageError(@TempDir Path dir) throws Exception {
        Path model = dir.resolve("lock.xta");
        Files.writeString(model, LOCK);
        CommandRun r = CommandRun.of("mutants", model.toString(), "--budget", "50", "--strategy", "goal", "--goal",
                "A[] Lock.Opening");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.err().startsWith("dtron mutants: --goal: "), r.err());
        assertTrue(!r.err().contains("\tat "), r.err());
    }

    private static Map<?, ?> mutants(Path dir, Path model, String strategy, String threads) throws Exception {
        Path json = dir.resolve(strategy + threads + ".json");
        CommandRun r = CommandRun.of("mutants", model.toString(), "--budget", "50", "--seeds", "3", "--seed", "1",
                "--threads", threads, "--strategy", strategy, "--json", json.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        return (Map<?, ?>) Json.parse(Files.readString(json));
    }

    private static Map<?, ?> mutant(Map<?, ?> report, String kind) {
        for (Object m : (List<?>) report.get("mutants")) {
            if (kind.equals(((Map<?, ?>) m).get("kind"))) {
                return (Map<?, ?>) m;
            }
        }
        throw new AssertionError("no mutant of kind " + kind + ": " + report);
    }

    private static List<String> statuses(Map<?, ?> report) {
        List<String> out = new ArrayList<>();
        for (Object m : (List<?>) report.get("mutants")) {
            Map<?, ?> mutant = (Map<?, ?>) m;
            out.add(mutant.get("number") + " " + mutant.get("status") + " " + mutant.get("seed"));
        }
        return out;
    }
}
