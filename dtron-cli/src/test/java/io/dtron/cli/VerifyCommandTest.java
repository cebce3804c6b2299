package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class VerifyCommandTest {
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
    private static final String FISCHER = """
            const int N = 2;
            typedef int[1,N] pid_t;
            int id = 0;
            process P(const pid_t pid) {
                clock x;
                state idle, req { x <= 2 }, wait, cs;
                init idle;
                trans idle -> req { guard id == 0; assign x = 0; },
                      req -> wait { assign x = 0, id = pid; },
                      wait -> req { guard id == 0; assign x = 0; },
                      wait -> cs { guard x > WAIT && id == pid; },
                      cs -> idle { assign id = 0; };
            }
            system P;
            """;

    private static Path fischer(Path dir, int wait) throws IOException {
        Path f = dir.resolve("fischer" + wait + ".xta");
        Files.writeString(f, "const int WAIT = " + wait + ";\n" + FISCHER);
        return f;
    }

    @Test
    void holdingQueriesExitWithZeroAndShowTheirFigures(@TempDir Path dir) throws IOException {
        CommandRun r = CommandRun.of("verify", fischer(dir, 2).toString(), "--query", "A[] not (P(1).cs and P(2).cs)",
                "--query", "E<> P(2).cs", "--trace", "none");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("2 queries from --query"), r.out());
        assertTrue(r.out().contains("[1] A[] not (P(1).cs and P(2).cs)\n    satisfied ("), r.out());
        assertTrue(r.out().matches("(?s).*states explored, [0-9,]+ stored, [0-9.]+ s, \\d+ MB\\).*"), r.out());
        assertTrue(r.out().contains("2 of 2 checked hold"), r.out());
        assertFalse(r.out().contains("witness"), "--trace none: " + r.out());
    }

    @Test
    void aViolatedQueryExitsWithTwoAndPrintsItsCounterexampleInTextOrJson(@TempDir Path dir) throws IOException {
        Path wrong = fischer(dir, 1);
        CommandRun text = CommandRun.of("verify", wrong.toString(), "--query", "A[] not (P(1).cs and P(2).cs)");
        assertEquals(2, text.exit(), text.out() + text.err());
        assertTrue(text.out().contains("NOT satisfied"), text.out());
        assertTrue(text.out().contains("counterexample:"), text.out());
        assertTrue(text.out().contains("P(1).cs, P(2).cs"), text.out());
        assertTrue(text.out().contains("concrete:"), text.out());
        assertTrue(text.out().contains("0 of 1 checked hold, 1 do not"), text.out());
        CommandRun json = CommandRun.of("verify", wrong.toString(), "--query", "A[] not (P(1).cs and P(2).cs)",
                "--trace", "json");
        assertEquals(2, json.exit());
        assertTrue(json.out().contains("    {\"states\":[{\"locations\":[\"P(1).idle\",\"P(2).idle\"]"), json.out());
    }

    @Test
    void livenessQueriesWithClocksAreAnswered(@TempDir Path dir) throws IOException {
        Path f = fischer(dir, 2);
        // wait is entered with x reset: x == 0 at that instant
        CommandRun holds = CommandRun.of("verify", f.toString(), "--query", "P(1).req --> P(1).wait and P(1).x == 0",
                "--trace", "none");
        assertEquals(0, holds.exit(), holds.out() + holds.err());
        assertTrue(holds.out().contains("1 of 1 checked hold"), holds.out());
        // P(1) alone may go round idle, req, wait, cs for ever (P(2) stays idle): x never passes 3
        CommandRun round = CommandRun.of("verify", f.toString(), "--query", "A<> P(1).x > 100");
        assertEquals(2, round.exit(), round.out() + round.err());
        assertTrue(round.out().contains("and then a cycle back to state"), round.out());
    }

    @Test
    void queriesFromAFileAndSkippedOnesAreListed(@TempDir Path dir) throws IOException {
        Path q = dir.resolve("q.q");
        Files.writeString(q, "// mutual exclusion\nA[] not (P(1).cs and P(2).cs)\nPr[<=10](<> P(1).cs)\n");
        CommandRun r = CommandRun.of("verify", fischer(dir, 2).toString(), "--queries", q.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("[2] Pr[<=10](<> P(1).cs)\n    skipped: a probability estimate"), r.out());
        assertTrue(r.out().contains("1 of 1 checked hold; 1 skipped"), r.out());
    }

    @Test
    void aStatisticalModelListsItsStatisticalQueriesAsSkippedAndSaysWhyTheOthersAreNotChecked(@TempDir Path dir)
            throws IOException {
        Path hybrid = dir.resolve("hybrid.xta");
        Files.writeString(hybrid, "const int WAIT = 2;\nclock h = 2.5;\n" + FISCHER);
        Path q = dir.resolve("q.q");
        Files.writeString(q, "Pr[<=10](<> P(1).cs)\nA[] not (P(1).cs and P(2).cs)\n");
        CommandRun r = CommandRun.of("verify", hybrid.toString(), "--queries", q.toString());
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("[1] Pr[<=10](<> P(1).cs)\n    skipped: a probability estimate"), r.out());
        assertTrue(r.out().contains("[2] A[] not (P(1).cs and P(2).cs)\n    not checked: the model cannot start: "
                + hybrid + ":2:11: error: real numbers (double) cannot be run by DTRON's engine"), r.out());
        assertTrue(r.out().contains("none checked: DTRON's engine cannot run the model; 1 skipped"), r.out());
        assertTrue(r.err().startsWith("dtron verify: " + hybrid + ": the model cannot start: "), r.err());
    }

    @Test
    void theModelsOwnQueriesAreTheDefault() {
        CommandRun r = CommandRun.of("verify", SHARED.resolve("benchmarks/fischer-4.xml").toString(), "--trace", "none");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("2 queries from the model"), r.out());
        assertTrue(r.out().contains("2 of 2 checked hold"), r.out());
    }

    @Test
    void aLimitGivesUnknownAndExitCodeThreeUnlessSomethingWorseHappened(@TempDir Path dir) throws IOException {
        Path grows = dir.resolve("grows.xta");
        Files.writeString(grows, """
                int[0,30000] i = 0;
                process P() { state a; init a; trans a -> a { guard i < 30000; assign i = i + 1; }; }
                system P;
                """);
        CommandRun r = CommandRun.of("verify", grows.toString(), "--query", "A[] i < 30000", "--time-limit", "0");
        assertEquals(3, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("unknown: the time limit was reached"), r.out());
        // the JVM running the tests holds more than 1 MB of heap, so the first check stops the search
        CommandRun memory = CommandRun.of("verify", grows.toString(), "--query", "A[] i < 30000", "--memory-limit",
                "1");
        assertEquals(3, memory.exit(), memory.out() + memory.err());
        assertTrue(memory.out().contains("unknown: the memory limit was reached after 1024 explored states"),
                memory.out());
        assertTrue(memory.out().contains("0 of 1 checked hold, 1 unknown"), memory.out());
        // a query that does not hold outweighs an unknown one: exit code 2
        CommandRun both = CommandRun.of("verify", grows.toString(), "--query", "A[] i < 30000", "--query",
                "A[] P.a and i > 0", "--time-limit", "0");
        assertTrue(both.out().contains("unknown: the time limit was reached"), both.out());
        assertTrue(both.out().contains("NOT satisfied"), both.out());
        assertEquals(2, both.exit(), both.out() + both.err());
        // an error (a query to fix) outweighs an unknown one (to retry with larger limits): exit code 1
        CommandRun error = CommandRun.of("verify", grows.toString(), "--query", "A[] i < 30000", "--query",
                "A[] j > 0", "--time-limit", "0");
        assertTrue(error.out().contains("unknown: the time limit was reached"), error.out());
        assertTrue(error.out().contains("error: query 'A[] j > 0', column 5: unknown name 'j'"), error.out());
        assertEquals(1, error.exit(), error.out() + error.err());
    }

    @Test
    void eachBadQueryOfAFileIsAnErrorAndTheOthersAreChecked(@TempDir Path dir) throws IOException {
        Path q = dir.resolve("q.q");
        Files.writeString(q, """
                // mutual exclusion, then two mistakes
                A[] not (P(1).cs and P(2).cs)
                E<> P(1).cs &&
                P(1).wait -->
                E<> P(2).cs
                """);
        CommandRun r = CommandRun.of("verify", fischer(dir, 2).toString(), "--queries", q.toString(), "--trace",
                "none");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("[1] A[] not (P(1).cs and P(2).cs)\n    satisfied"), r.out());
        assertTrue(r.out().contains("[2] E<> P(1).cs &&\n    error: line 3: query 'E<> P(1).cs &&', column "),
                r.out());
        assertTrue(r.out().contains("[3] P(1).wait -->\n    error: line 4: query 'P(1).wait -->', column "),
                r.out());
        assertTrue(r.out().contains("[4] E<> P(2).cs\n    satisfied"), r.out());
        assertTrue(r.out().contains("2 of 2 checked hold; 2 in error"), r.out());
        assertTrue(r.err().contains("dtron verify: " + q + ": line 3: query 'E<> P(1).cs &&', column "), r.err());
        assertFalse(r.err().contains("Exception") || r.err().contains("\tat "), "no stack trace: " + r.err());
        // a query that does not hold comes first: exit code 2 even with errors
        Files.writeString(q, "E<> P(1).cs and P(2).cs\noops\n");
        CommandRun violated = CommandRun.of("verify", fischer(dir, 2).toString(), "--queries", q.toString());
        assertEquals(2, violated.exit(), violated.out() + violated.err());
        assertTrue(violated.out().contains("0 of 1 checked hold, 1 do not; 1 in error"), violated.out());
    }

    @Test
    void errorsAreOneLineAndExitWithOne(@TempDir Path dir) throws IOException {
        Path f = fischer(dir, 2);
        CommandRun syntax = CommandRun.of("verify", f.toString(), "--query", "E<> P(1).cs &&");
        assertEquals(1, syntax.exit());
        assertTrue(syntax.err().startsWith("dtron verify: " + f + ": query 'E<> P(1).cs &&', column "), syntax.err());
        CommandRun noQueries = CommandRun.of("verify", f.toString());
        assertEquals(1, noQueries.exit());
        assertTrue(noQueries.err().contains("has no queries: give --query Q or --queries FILE.q"), noQueries.err());
        CommandRun missing = CommandRun.of("verify", dir.resolve("nope.xml").toString(), "--query", "E<> true");
        assertEquals(1, missing.exit());
        assertTrue(missing.err().contains("nope.xml: error: no such file"), missing.err());
        Path bad = dir.resolve("bad.xta");
        Files.writeString(bad, "int i;\nprocess P() { state a; init a; trans a -> a { assign j = 1; }; }\nsystem P;\n");
        CommandRun model = CommandRun.of("verify", bad.toString(), "--query", "E<> true");
        assertEquals(1, model.exit());
        assertTrue(model.err().contains(bad + ": 1 error"), model.err());
        for (CommandRun r : new CommandRun[] {syntax, noQueries, missing, model}) {
            assertFalse(r.err().contains("Exception") || r.err().contains("\tat "), "no stack trace: " + r.err());
        }
    }

    @Test
    void aModelErrorOnOneQuerysSearchIsThatQuerysErrorAndTheOthersAreChecked(@TempDir Path dir) throws IOException {
        // the index goes out of range only once i reaches 3: a search that gets there meets a model error
        Path model = dir.resolve("range.xta");
        Files.writeString(model, "int a[3];\nint i;\nprocess P() { state s, t; init s;\n"
                + "  trans s -> s { guard i < 3; assign i = i + 1; }, s -> t { assign a[i] = 1; }; }\nsystem P;\n");
        CommandRun r = CommandRun.of("verify", model.toString(), "--query", "E<> P.t and i == 3", "--query",
                "E<> P.t and i == 1");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("[1] E<> P.t and i == 3\n    error: "), r.out());
        assertTrue(r.err().contains("dtron verify: " + model + ": model error while checking 'E<> P.t and i == 3'"),
                r.err());
        assertTrue(r.out().contains("[2] E<> P.t and i == 1\n    satisfied"), r.out());
        assertTrue(r.out().contains("1 of 1 checked hold; 1 in error"), r.out());
        assertFalse(r.err().contains("\tat "), "no stack trace: " + r.err());
    }
}
