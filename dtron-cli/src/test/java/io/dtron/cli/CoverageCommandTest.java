package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.coverage.Coverage;
import io.dtron.testadapter.BusTicker;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.UUID;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** The coverage of dtron run (the summary, --coverage, --until, --traps, the trace) and dtron coverage merge. */
class CoverageCommandTest {
    private static final String TICKER = """
            chan i_reset, o_tick;
            int[0,999] o_tick_seq;
            bool trap_reset;
            process Ticker() { clock x; state Running { x <= 12 }; init Running;
                trans Running -> Running { guard x >= 8; sync o_tick!; assign o_tick_seq = (o_tick_seq + 1) % 1000, x = 0; },
                      Running -> Running { sync i_reset?; assign x = 0, o_tick_seq = 0, trap_reset = true; }; }
            process Env() { clock e; state Watching; init Watching;
                trans Watching -> Watching { guard e >= 25; sync i_reset!; assign e = 0; },
                      Watching -> Watching { sync o_tick?; }; }
            system Ticker, Env;
            """;
    private static final String SUMMARY = "coverage: locations 2/2 (100.0%), edges 4/4 (100.0%) of reachable"
            + " (environment 2/2 (100.0%), implementation 2/2 (100.0%)); traps 1/1 (100.0%)";

    @TempDir
    Path dir;

    private Path model() throws IOException {
        return Files.writeString(dir.resolve("ticker.xta"), TICKER);
    }

    private CommandRun run(Path model, long seed, String... more) {
        List<String> args = new java.util.ArrayList<>(List.of("run", model.toString(), "--sut",
                TickerForTests.class.getName(), "--virtual-time", "--seed", Long.toString(seed), "--timeout", "300"));
        args.addAll(List.of(more));
        return CommandRun.of(args.toArray(String[]::new));
    }

    @Test
    void theSummaryFollowsTheStatisticsAndTheFileReadsBackAsWritten() throws IOException {
        Path json = dir.resolve("one.json");
        CommandRun r = run(model(), 7, "--coverage", json.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        List<String> lines = r.out().lines().toList();
        assertTrue(lines.get(lines.size() - 2).startsWith("statistics: 7 PASSED"), r.out());
        assertEquals(SUMMARY, lines.get(lines.size() - 1));
        String text = Files.readString(json);
        Coverage c = CoverageJson.read(text);
        assertEquals(SUMMARY, c.summary());
        assertEquals(List.of(7L), c.seeds());
        assertEquals(text, CoverageJson.write(c), "what is read is what was written");
    }

    @Test
    void theTraceHasTheEdgesOfEveryStep() throws IOException {
        Path trace = dir.resolve("trace.jsonl");
        assertEquals(0, run(model(), 7, "--trace", trace.toString()).exit());
        List<String> lines = Files.readAllLines(trace);
        int firstInput = 0;
        while (!lines.get(firstInput).contains("\"kind\":\"input\"")) {
            firstInput++;
        }
        String edges = lines.get(firstInput + 1);
        assertTrue(edges.startsWith("{\"kind\":\"edges\",\"t_us\":"), edges);
        assertTrue(edges.endsWith(",\"channel\":\"reset\",\"input\":true,\"certainly\":[\"Ticker: Running -> Running"
                + " i_reset?\",\"Env: Watching -> Watching i_reset!\"],\"possibly\":[]}"), edges);
    }

    @Test
    void aStopConditionEndsTheRunAndABadOneIsAUsageErrorWithItsColumn() throws IOException {
        Path m = model();
        CommandRun stopped = run(m, 7, "--until", "trap_coverage(100) and inputs(2)");
        assertEquals(0, stopped.exit(), stopped.out() + stopped.err());
        assertTrue(stopped.out().contains("PASSED: the stop condition trap_coverage(100) and inputs(2) was met at t="),
                stopped.out());
        assertTrue(stopped.out().contains(" by trap_coverage(100) and inputs(2), after 2 inputs and "), stopped.out());

        CommandRun bad = run(m, 7, "--until", "inputs(2) or");
        assertEquals(1, bad.exit());
        assertEquals("dtron run: --until 'inputs(2) or': column 13: expected a condition, found the end\n"
                + "see 'dtron run --help'\n", bad.err());
        CommandRun goal = run(m, 7, "--until", "reached(1)");
        assertEquals(1, goal.exit());
        assertTrue(goal.err().startsWith("dtron run: --until 'reached(1)': column 1: reached(1) asks for goal 1, but"
                + " the run has no goals (give them with --goal)\n"), goal.err());
        CommandRun traps = run(m, 7, "--traps", "trap_reset,nope");
        assertEquals(1, traps.exit());
        assertTrue(traps.err().startsWith("dtron run: --traps: no bool variable or array called nope to count as a"
                + " trap\n"), traps.err());
        assertFalse(bad.err().contains("\tat ") || goal.err().contains("\tat ") || traps.err().contains("\tat "));
    }

    @Test
    void mergeCountsSeedsAsOneSuiteAndRefusesOtherModelsAndOtherFiles() throws IOException {
        Path m = model();
        Path a = dir.resolve("a.json");
        Path b = dir.resolve("b.json");
        Path all = dir.resolve("all.json");
        // seed 1 stops at its first input; seed 2 runs to the end
        assertEquals(0, run(m, 1, "--coverage", a.toString(), "--until", "inputs(1)").exit());
        assertEquals(0, run(m, 2, "--coverage", b.toString()).exit());
        CommandRun merged = CommandRun.of("coverage", "merge", a.toString(), b.toString(), "-o", all.toString());
        assertEquals(0, merged.exit(), merged.out() + merged.err());
        assertEquals(SUMMARY + "; 2 runs\n", merged.out());
        Coverage union = CoverageJson.read(Files.readString(all));
        assertEquals(List.of(1L, 2L), union.seeds());
        assertEquals(CoverageJson.read(Files.readString(a)).channels().get(0).count()
                + CoverageJson.read(Files.readString(b)).channels().get(0).count(), union.channels().get(0).count());

        Path other = Files.writeString(dir.resolve("other.xta"), TICKER.replace("x <= 12", "x <= 13")
                .replace("state Watching;", "state Watching, Away;"));
        Path c = dir.resolve("c.json");
        assertEquals(0, run(other, 1, "--coverage", c.toString()).exit());
        CommandRun refused = CommandRun.of("coverage", "merge", a.toString(), c.toString());
        assertEquals(1, refused.exit());
        assertTrue(refused.err().startsWith("dtron coverage merge: " + c + " is the coverage of another model than "
                + a + " (" + other + ", fingerprint "), refused.err());
        assertEquals("", refused.out());

        // a run counts once: a file given twice, by any path, or a copy of one, is refused, nothing written
        Path twice = dir.resolve("twice.json");
        CommandRun same = CommandRun.of("coverage", "merge", a.toString(), b.toString(),
                dir.resolve(".").resolve("a.json").toString(), "-o", twice.toString());
        assertEquals(1, same.exit(), same.out() + same.err());
        assertEquals("dtron coverage merge: " + dir.resolve(".").resolve("a.json") + " is given twice (as " + a
                + " too): a run counts once in a suite\n", same.err());
        assertFalse(Files.exists(twice));
        Path copy = Files.copy(b, dir.resolve("copy.json"));
        CommandRun copied = CommandRun.of("coverage", "merge", b.toString(), copy.toString());
        assertEquals(1, copied.exit(), copied.out() + copied.err());
        assertEquals("dtron coverage merge: " + copy + " is a copy of " + b + ": a run counts once in a suite\n",
                copied.err());

        Path notCoverage = Files.writeString(dir.resolve("x.json"), "{\"kind\": \"start\"}");
        CommandRun wrong = CommandRun.of("coverage", "merge", a.toString(), notCoverage.toString());
        assertEquals(1, wrong.exit());
        assertEquals("dtron coverage merge: " + notCoverage + ": not a DTRON coverage file of version 1 (no"
                + " \"dtron_coverage\": 1)\n", wrong.err());
        CommandRun missing = CommandRun.of("coverage", "merge", dir.resolve("none.json").toString());
        assertEquals(1, missing.exit());
        assertTrue(missing.err().startsWith("dtron coverage merge: cannot read " + dir.resolve("none.json")),
                missing.err());
    }

    @Test
    void aRealTimeRunOnTheBusPrintsTheSummaryToo() throws IOException {
        Path json = dir.resolve("bus.json");
        // 25 ms per unit, as RunCommandTest's bus run: the ticker's 4 units of jitter hold on a busy machine
        CommandRun r = CommandRun.of(model().toString(), "--adapter", BusTicker.class.getName(), "--cluster",
                "cov-" + UUID.randomUUID(), "--timeunit", "25000", "--timeout", "60", "--delay-policy", "eager",
                "--seed", "3", "--coverage", json.toString());
        assertNotEquals(1, r.exit(), r.out() + r.err());
        // whatever the verdict a busy machine gives, the summary follows the statistics, of the same model
        List<String> lines = r.out().lines().toList();
        int statistics = 0;
        while (statistics < lines.size() && !lines.get(statistics).startsWith("statistics: 3 ")) {
            statistics++;
        }
        assertTrue(statistics < lines.size() - 1, r.out());
        assertTrue(lines.get(statistics + 1).matches("coverage: locations \\d/2 \\(.*\\), edges \\d/4 \\(.*\\) of"
                + " reachable \\(environment \\d/2 .*"), r.out());
        assertEquals(lines.get(statistics + 1), CoverageJson.read(Files.readString(json)).summary());
    }
}
