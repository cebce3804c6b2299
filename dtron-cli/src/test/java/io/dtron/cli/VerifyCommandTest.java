package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
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
        assertTrue(json.out().startsWith("{\"states\":[{\"locations\":[\"P(1).idle\",\"P(2).idle\"]"), json.out());
    }

    @Test
    void withJsonTracesStandardOutputHoldsTheTracesAloneOneALineAndTheTextGoesToStandardError(@TempDir Path dir)
            throws IOException {
        Path wrong = fischer(dir, 1);
        Path q = dir.resolve("q.q");
        Files.writeString(q, """
                E<> P(1).cs
                A[] not (P(1).cs and P(2).cs)
                A[] P(1).x >= 0
                E<> P(1).css
                Pr[<=10](<> P(1).cs)
                """);
        CommandRun r = CommandRun.of("verify", wrong.toString(), "--queries", q.toString(), "--trace", "json");
        assertEquals(2, r.exit(), "a query does not hold, as with text: " + r.out() + r.err());
        List<String> lines = r.out().lines().toList();
        assertEquals(2, lines.size(), "one trace a line, for the witness of [1] and the counterexample of [2]: "
                + r.out());
        List<String> last = new ArrayList<>();
        for (String line : lines) {
            Map<?, ?> trace = (Map<?, ?>) Json.parse(line);
            List<?> states = (List<?>) trace.get("states");
            last.add(String.valueOf(((Map<?, ?>) states.get(states.size() - 1)).get("locations")));
            assertEquals(states.size() - 1, ((List<?>) trace.get("transitions")).size(), line);
        }
        assertTrue(last.get(0).contains("P(1).cs"), "the witness of E<> P(1).cs ends in it: " + last);
        assertTrue(last.get(1).contains("P(1).cs") && last.get(1).contains("P(2).cs"), "the counterexample: " + last);
        String err = r.err();
        assertTrue(err.startsWith(wrong + ": 5 queries from " + q + "\n[1] E<> P(1).cs\n    satisfied ("), err);
        assertTrue(err.contains("    witness: on standard output, JSON\n[2] A[] not (P(1).cs and P(2).cs)\n"
                + "    NOT satisfied ("), err);
        assertTrue(err.contains("    counterexample: on standard output, JSON\n[3] A[] P(1).x >= 0\n    satisfied ("),
                err);
        String error = "line 4: query 'E<> P(1).css', column 10: process P(1) has no location 'css' (did you mean"
                + " 'cs'?)";
        assertTrue(err.contains("[4] E<> P(1).css\n    error: " + error + "\n[5] Pr"), err);
        assertEquals(err.indexOf(error), err.lastIndexOf(error), "the error once: " + err);
        assertTrue(err.endsWith("2 of 3 checked hold, 1 do not; 1 skipped; 1 in error\n"), err);
        // a query without a trace writes nothing to standard output; an error, or none, keep their exit codes
        CommandRun holds = CommandRun.of("verify", fischer(dir, 2).toString(), "--query", "A[] P(1).x >= 0",
                "--trace", "json");
        assertEquals(0, holds.exit(), holds.err());
        assertEquals("", holds.out());
        CommandRun bad = CommandRun.of("verify", fischer(dir, 2).toString(), "--query", "E<> Q(1).cs", "--trace",
                "json");
        assertEquals(1, bad.exit(), bad.err());
        assertEquals("", bad.out());
        assertTrue(bad.err().contains("    error: query 'E<> Q(1).cs', column 5: unknown process 'Q(1)' (did you mean"
                + " 'P(1)'?)"),
                bad.err());
    }

    @Test
    void aWrongNameInAQueryIsReportedWithItsColumnAndTheNearestNames(@TempDir Path dir) throws IOException {
        Path f = fischer(dir, 2);
        CommandRun r = CommandRun.of("verify", f.toString(), "--query", "E<> P(1).wiat", "--query",
                "A[] P(1) == cs imply id > 0", "--query", "A[] P(1).cs implies id == 1", "--trace", "none");
        assertEquals(1, r.exit(), r.out() + r.err());
        String[] errors = {
            "query 'E<> P(1).wiat', column 10: process P(1) has no location 'wiat' (did you mean 'wait'?)",
            "query 'A[] P(1) == cs imply id > 0', column 5: 'P(1)' is a process, not a value: P(1).cs tests whether it"
                    + " is in location cs",
            "query 'A[] P(1).cs implies id == 1', column 13: 'implies' is not an operator of queries: implication is"
                    + " written imply, as in p imply q"};
        for (String error : errors) {
            assertTrue(r.out().contains("    error: " + error + "\n"), r.out());
            assertTrue(r.err().contains("dtron verify: " + f + ": " + error + "\n"), r.err());
        }
        Path q = dir.resolve("q.q");
        Files.writeString(q, "// a typo\nE<> PP(2).cs\n");
        CommandRun file = CommandRun.of("verify", f.toString(), "--queries", q.toString());
        assertEquals(1, file.exit(), file.out() + file.err());
        assertTrue(file.err().contains("dtron verify: " + q + ": line 2: query 'E<> PP(2).cs', column 5: unknown"
                + " process 'PP(2)' (did you mean 'P(2)'?)"), file.err());
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
        // limits that no clock or heap could reach are refused, not wrapped around
        for (String[] limit : new String[][] {{"--memory-limit", "9223372036854775807"}, {"--time-limit", "NaN"},
                {"--time-limit", "1e300"}}) {
            CommandRun huge = CommandRun.of("verify", grows.toString(), "--query", "A[] i < 30000", limit[0],
                    limit[1]);
            assertEquals(1, huge.exit(), huge.out() + huge.err());
            assertTrue(huge.err().startsWith("dtron verify: --time-limit must be a number of seconds from 0 to"
                    + " 9223372036 (about 292 years) and --memory-limit a positive number of MB, at most"
                    + " 8796093022207"), huge.err());
        }
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
