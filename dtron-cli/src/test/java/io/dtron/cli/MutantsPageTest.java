package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.ShellWords;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Map;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The sessions of the mutants page ({@code mutants.md}) run as written, on the page's model {@code beeper.xta}
 * (the model whose mutants {@code MutantsTest} counts by hand): every line the page shows is printed, in its order;
 * {@code ...} in a line stands for any text (the wall time and rate of a mutation run).
 */
class MutantsPageTest {
    private static final String COMMAND = "$ java -jar dtron.jar ";

    @Test
    void theSessionsPrintWhatThePageShows(@TempDir Path dir) throws Exception {
        DocPage page = DocPage.read("mutants.md");
        String model = page.blockAfter("The beeper, `beeper.xta`:").code();
        assertEquals(Files.readString(Path.of("../dtron-engine/src/test/resources/io/dtron/engine/sim/beeper.xta"),
                StandardCharsets.UTF_8), model, "the page's beeper is MutantsTest's");
        Files.writeString(dir.resolve("beeper.xta"), model);
        List<DocPage.Block> sessions = page.blocksStartingWith(COMMAND);
        assertEquals(2, sessions.size(), "a run against the model, and its mutants");
        Map<String, Integer> exits = Map.of("run", 0, "mutants", 0);
        for (DocPage.Block b : sessions) {
            List<String> lines = new ArrayList<>(b.code().lines().toList());
            List<String> args = new ArrayList<>(Arrays.asList(lines.remove(0).substring(COMMAND.length()).split(" ")));
            args.set(1, dir.resolve(args.get(1)).toString());
            CommandRun r = CommandRun.of(args.toArray(String[]::new));
            assertFalse(r.err().contains("\tat "), "no stack trace: " + r.err());
            assertEquals(exits.get(args.get(0)), r.exit(), r.out() + r.err());
            List<String> out = ShellWords.lines(r.out(), dir);
            assertEquals(lines.size(), out.size(), "mutants.md line " + b.line() + ": the lines printed\n" + r.out());
            for (int i = 0; i < lines.size(); i++) {
                assertTrue(pattern(lines.get(i)).matcher(out.get(i)).matches(), "mutants.md, the session on line "
                        + b.line() + ": '" + lines.get(i) + "' was printed as '" + out.get(i) + "'");
            }
        }
    }

    @Test
    void theJsonHasEveryMutantWithItsStatus(@TempDir Path dir) throws Exception {
        String model = DocPage.read("mutants.md").blockAfter("The beeper, `beeper.xta`:").code();
        Files.writeString(dir.resolve("beeper.xta"), model);
        Path json = dir.resolve("m.json");
        CommandRun r = CommandRun.of("mutants", dir.resolve("beeper.xta").toString(), "--budget", "100", "--seeds",
                "10", "--seed", "1", "--json", json.toString(), "--delay-policy", "eager");
        assertEquals(0, r.exit(), r.out() + r.err());
        Map<?, ?> root = (Map<?, ?>) Json.parse(Files.readString(json));
        assertEquals("eager", root.get("delay_policy"));
        assertEquals(List.of(1L, 2L, 3L, 4L, 5L, 6L, 7L, 8L, 9L, 10L), root.get("seeds"));
        assertEquals(100L, root.get("budget"));
        assertEquals(6L, root.get("equivalent"));
        assertEquals(0L, root.get("invalid"));
        assertEquals(10L, root.get("model_runs_passed"));
        List<?> mutants = (List<?>) root.get("mutants");
        assertEquals(16, mutants.size());
        Map<?, ?> value = (Map<?, ?>) mutants.get(8);
        assertEquals("output value", value.get("kind"));
        assertEquals("killed", value.get("status"));
        assertTrue(value.get("where").toString().endsWith("beeper.xta:12"), value.toString());
        assertTrue(value.get("explanation").toString().contains("beep(n=2)"), value.toString());
    }

    @Test
    void optionsOfOneRunAgainstOneSystemAreRefused(@TempDir Path dir) throws Exception {
        String model = DocPage.read("mutants.md").blockAfter("The beeper, `beeper.xta`:").code();
        String file = Files.writeString(dir.resolve("beeper.xta"), model).toString();
        CommandRun sut = CommandRun.of("mutants", file, "--sut", "model");
        assertEquals(1, sut.exit());
        assertTrue(sut.err().startsWith("dtron mutants: --sut is an option of a run against one system under test"),
                sut.err());
        CommandRun timeout = CommandRun.of("mutants", file, "--timeout", "5");
        assertEquals(1, timeout.exit());
        assertTrue(timeout.err().startsWith("dtron mutants: --timeout is dtron run's: give each mutant's run its"
                + " time units with --budget"), timeout.err());
        CommandRun coverage = CommandRun.of("mutants", file, "--coverage", dir.resolve("c.json").toString());
        assertEquals(1, coverage.exit());
        assertTrue(coverage.err().startsWith("dtron mutants: --coverage is an option of one run's coverage"),
                coverage.err());
        assertFalse(Files.exists(dir.resolve("c.json")));
        CommandRun until = CommandRun.of("mutants", file, "--until", "time(1)");
        assertEquals(1, until.exit());
        assertTrue(until.err().startsWith("dtron mutants: --until is an option of one run's coverage"), until.err());
        CommandRun policy = CommandRun.of("mutants", file, "--delay-policy", "sometimes");
        assertEquals(1, policy.exit());
        assertTrue(policy.err().startsWith("dtron mutants: unknown delay policy 'sometimes'"), policy.err());
        CommandRun realTime = CommandRun.of("run", file, "--sut", "model");
        assertEquals(1, realTime.exit());
        assertTrue(realTime.err().startsWith("dtron run: --sut model runs in virtual time: add --virtual-time"),
                realTime.err());
        CommandRun seed = CommandRun.of("run", file, "--sut-seed", "3", "--virtual-time", "--sut",
                "io.dtron.cli.TickerForTests");
        assertEquals(1, seed.exit());
        assertTrue(seed.err().startsWith("dtron run: --sut-seed is the seed of --sut model"), seed.err());
    }

    /** A line of the page as a pattern: "..." is any text. */
    private static Pattern pattern(String expected) {
        String[] parts = expected.split(Pattern.quote("..."), -1);
        StringBuilder regex = new StringBuilder();
        for (int i = 0; i < parts.length; i++) {
            regex.append(i == 0 ? "" : ".*").append(Pattern.quote(parts[i]));
        }
        return Pattern.compile(regex.toString());
    }
}
