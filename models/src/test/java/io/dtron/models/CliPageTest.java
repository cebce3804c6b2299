package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.cli.DtronCommand;
import io.dtron.models.ticker.TickerBusAdapter;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.LogCapture;
import io.dtron.testsupport.ShellWords;
import io.dtron.testsupport.Waits;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The {@code $ java -jar dtron.jar ...} sessions of the command line page ({@code cli.md}) run as written, in this
 * JVM, in a folder holding the models they name: {@code LightContr.xml} and {@code .trn} and {@code decl-04.xta}
 * from the shared models, the bundled {@code ticker.xml}, and the page's own {@code q.xml} and {@code broken.xml};
 * {@code models/target/classes} is this module's classes.
 * A line of a session is a line the command printed, on standard output or on standard error, each stream's lines in
 * their order; a line {@code ...} stands for any lines. Sessions in virtual time, of {@code check} and of usage
 * errors print exactly what the page shows; a real-time run prints lines that begin as the page's do, up to their
 * first number (its seed, its counts, its timings and member ids differ), in their order, with the same verdict, or,
 * when a busy machine held the run's threads up, INCONCLUSIVE naming the event that came too late, or FAILED on a
 * tick that the bundled ticker says it published late.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class CliPageTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
    private static final String PROMPT = "$ java -jar dtron.jar ";
    private static final Pattern DIGIT = Pattern.compile("\\d");
    /** The verdict of a real-time run whose threads a busy machine held up past a window of the model. */
    private static final Pattern HELD_UP = Pattern.compile(
            "(?m)^INCONCLUSIVE: .*(input executed too late|more than the reorder window)");

    /**
     * A session: its command's first two words as the page shows them, the command's arguments, the lines the page
     * shows after it, and the page's line of the command.
     */
    private record Session(String shown, List<String> args, List<String> expected, int line) {
        boolean realTime() {
            return !args.contains("--virtual-time") && !args.get(0).equals("check") && !args.get(0).equals("delta")
                    && !expected.stream().anyMatch(l -> l.startsWith("see 'dtron "));
        }
    }

    @Test
    void everySessionPrintsWhatThePageShows(@TempDir Path dir) throws Exception {
        Files.copy(SHARED.resolve("tron/LightContr.xml"), dir.resolve("LightContr.xml"));
        Files.copy(SHARED.resolve("tron/LightContr.trn"), dir.resolve("LightContr.trn"));
        Files.copy(SHARED.resolve("xta-syntax/decl-04.xta"), dir.resolve("decl-04.xta"));
        Files.copy(ROOT.resolve("models/src/main/resources/io/dtron/models/ticker.xml"), dir.resolve("ticker.xml"));
        DocPage page = DocPage.read("cli.md");
        Files.writeString(dir.resolve("q.xml"), page.blockAfter("On this `q.xml`").code());
        Files.writeString(dir.resolve("broken.xml"), page.blockAfter("and this `broken.xml`").code());
        List<String> exits = new ArrayList<>();
        for (Session s : sessions(page, dir)) {
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            int exit;
            List<String> lateTicks;
            try (LogCapture ticker = new LogCapture(TickerBusAdapter.class)) {
                if (s.args().contains("lab")) {
                    exit = withTheAdaptersTicker(s, out, err);
                } else {
                    exit = DtronCommand.run(s.args().toArray(String[]::new), new PrintWriter(out, true),
                            new PrintWriter(err, true));
                }
                lateTicks = ticker.messages().stream().filter(m -> m.contains("this JVM was held up")).toList();
            }
            assertFalse(err.toString().contains("\tat "), "no stack trace: " + err);
            // a busy machine may hold a real-time run's threads up longer than the model's windows allow: where the
            // page shows PASSED, the tester then says INCONCLUSIVE naming the event that came too late, or FAILED on
            // a tick that the ticker itself says it published late (the page's way to tell a FAILED verdict from a
            // wrong one)
            boolean heldUp = s.realTime() && (exit == 3 && HELD_UP.matcher(out.toString()).find()
                    || exit == 2 && !lateTicks.isEmpty() && out.toString().contains("\nFAILED: output tick("));
            match(s, heldUp, ShellWords.lines(out.toString(), dir), ShellWords.lines(err.toString(), dir));
            exits.add(s.shown() + ": " + (heldUp ? 0 : exit));
        }
        // each session this test runs, by its command's first words, and its exit code: the page's verdicts
        assertEquals(List.of("check LightContr.xml: 0", "check q.xml: 0", "check decl-04.xta: 1",
                "check broken.xml: 1", "run LightContr.xml: 0",
                "run LightContr.xml: 2", "run ticker.xml: 1", "ticker.xml --cluster: 0", "ticker.xml --classpath: 0"),
                exits);
    }

    /**
     * Runs the tester of adapters.md's ticker adapter (member {@code ticker-adapter} of bus {@code lab}) as the page
     * does: the tester waits for it, then it joins. The bundled ticker stands in for the page's adapter (the same
     * ticks, resets and declared outputs); {@code FreshProjectIT} builds and runs the page's own.
     */
    private static int withTheAdaptersTicker(Session s, StringWriter out, StringWriter err) throws Exception {
        CompletableFuture<Integer> tester = CompletableFuture.supplyAsync(() -> DtronCommand.run(
                s.args().toArray(String[]::new), new PrintWriter(out, true), new PrintWriter(err, true)));
        Waits.await("the tester waits for the adapter").until(() -> out.toString().contains("dtron run: waiting")
                || tester.isDone());
        try (Dtron bus = Dtron.connect(DtronOptions.builder().clusterName("lab").memberName("ticker-adapter")
                .build()); TickerBusAdapter ticker = new TickerBusAdapter()) {
            ticker.start(bus);
            return tester.get(60, TimeUnit.SECONDS);
        }
    }

    /**
     * The page's sessions, with the files' names resolved in {@code dir} and the models' classes in this build; the
     * page's {@code delta} session is {@code DeltaCommandTest}'s (it writes a file).
     */
    private static List<Session> sessions(DocPage page, Path dir) {
        List<Session> sessions = new ArrayList<>();
        for (DocPage.Block b : page.blocksStartingWith(PROMPT)) {
            List<String> lines = b.code().lines().toList();
            for (int i = 0; i < lines.size(); ) {
                int line = b.line() + 1 + i;
                StringBuilder command = new StringBuilder();
                while (lines.get(i).endsWith("\\")) {
                    command.append(lines.get(i), 0, lines.get(i).length() - 1).append(' ');
                    i++;
                }
                command.append(lines.get(i++));
                List<String> expected = new ArrayList<>();
                while (i < lines.size() && !lines.get(i).startsWith("$ ")) {
                    expected.add(lines.get(i++));
                }
                List<String> args = new ArrayList<>(List.of(command.substring(PROMPT.length()).trim().split("\\s+")));
                if (args.get(0).equals("delta")) {
                    continue;
                }
                for (int a = 0; a < args.size(); a++) {
                    String arg = args.get(a);
                    if (arg.matches("[\\w-]+\\.(xml|xta|trn)")) {
                        assertTrue(Files.exists(dir.resolve(arg)), "cli.md, line " + line + ": no " + arg);
                        args.set(a, dir.resolve(arg).toString());
                    } else if (arg.equals("models/target/classes")) {
                        args.set(a, ROOT.resolve(arg).toString());
                    }
                }
                sessions.add(new Session(String.join(" ", List.of(command.substring(PROMPT.length()).trim()
                        .split("\\s+")).subList(0, 2)), args, expected, line));
            }
        }
        return sessions;
    }

    /**
     * Every line of the session is a line of standard output or of standard error, each stream's lines in their
     * order, and nothing else is printed unless the session shows {@code ...}; in real time, the lines' beginnings
     * up to their first number, and other lines (a warning that the machine is busy) may come between; an
     * INCONCLUSIVE or FAILED verdict stands for PASSED when the run was {@code heldUp}, and ends the comparison.
     */
    private static void match(Session s, boolean heldUp, List<String> out, List<String> err) {
        int o = 0;
        int e = 0;
        boolean more = s.realTime();
        String printed = "\nstandard output:\n" + String.join("\n", out) + "\nstandard error:\n" + String.join("\n", err);
        for (String expected : s.expected()) {
            if (expected.strip().equals("...")) {
                more = true;
                continue;
            }
            Pattern p = heldUp && expected.startsWith("PASSED: ") ? Pattern.compile("(INCONCLUSIVE|FAILED): .*")
                    : pattern(expected, s.realTime());
            int atOut = find(p, out, o, more);
            int atErr = atOut >= 0 ? -1 : find(p, err, e, more);
            if (atOut >= 0) {
                o = atOut + 1;
            } else if (atErr >= 0) {
                e = atErr + 1;
            } else {
                fail("cli.md, the session on line " + s.line() + ": '" + expected + "' was not printed where the page"
                        + " shows it" + printed);
            }
            more = s.realTime();
            if (heldUp && expected.startsWith("PASSED: ")) {
                return; // what follows the verdict describes a run that ended early: other channels, other figures
            }
        }
        if (!more && !s.realTime() && (o < out.size() || e < err.size())) {
            fail("cli.md, the session on line " + s.line() + " prints more than the page shows" + printed);
        }
    }

    /** The first line from {@code from} that matches, or -1; unless {@code more}, only the line at {@code from}. */
    private static int find(Pattern p, List<String> lines, int from, boolean more) {
        for (int i = from; i < lines.size() && (more || i == from); i++) {
            if (p.matcher(lines.get(i)).matches()) {
                return i;
            }
        }
        return -1;
    }

    /** A session line as a pattern: in real time, the line's beginning, up to its first number, and any text. */
    private static Pattern pattern(String expected, boolean realTime) {
        Matcher number = DIGIT.matcher(expected);
        return !realTime ? Pattern.compile(Pattern.quote(expected))
                : Pattern.compile(Pattern.quote(number.find() ? expected.substring(0, number.start()) : expected) + ".*");
    }
}
