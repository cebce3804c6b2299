package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.ShellWords;
import io.dtron.testsupport.Tools;
import java.io.File;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The sessions of the verify page ({@code verify.md}) run as written: on the page's own model {@code crossing.xta}
 * and on Uppaal's {@code bridge.xml} and {@code train-gate.xml} from the shared models. A line of a session is a line the command printed, on
 * standard output or on standard error, in the order of each; {@code ...} stands for any text, and the time and
 * memory of a query's figures may differ.
 */
class VerifyPageTest {
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
    private static final String COMMAND = "$ java -jar dtron.jar verify ";
    private static final Pattern FIGURES = Pattern.compile("\\d+\\.\\d\\d s, \\d+ MB");

    /** A session's command: dtron's arguments, whether standard error is dropped, and the jq command it pipes into. */
    private record Session(List<String> args, boolean dropErr, List<String> jq, List<String> expected, int line) {
    }

    @Test
    void theSessionsWithoutJqPrintWhatThePageShows(@TempDir Path dir) throws IOException {
        List<Session> sessions = sessions(dir).stream().filter(s -> s.jq().isEmpty()).toList();
        // each model's session, and its exit code: a query does not hold (2), queries in error (1)
        Map<String, Integer> exits = Map.of("bridge.xml", 2, "crossing.xta", 1, "train-gate.xml", 1);
        assertEquals(exits.keySet().stream().sorted().toList(), sessions.stream().map(s -> s.args().get(1))
                .map(a -> Path.of(a).getFileName().toString()).sorted().toList(), "the sessions this test runs");
        for (Session s : sessions) {
            CommandRun r = CommandRun.of(s.args().toArray(String[]::new));
            assertFalse(r.err().contains("\tat "), "no stack trace: " + r.err());
            match(s, ShellWords.lines(r.out(), dir), s.dropErr() ? List.of() : ShellWords.lines(r.err(), dir));
            assertEquals(exits.get(Path.of(s.args().get(1)).getFileName().toString()), r.exit(), r.out() + r.err());
            if (s.args().get(1).endsWith("crossing.xta")) {
                // the errors, dropped by 2>/dev/null on the page, are on standard error with the model's name
                assertTrue(r.err().contains("dtron verify: " + dir.resolve("crossing.xta") + ": query 'E<> Trian.Cross',"
                        + " column 5: unknown process 'Trian' (did you mean 'Train'?)"), r.err());
            }
        }
    }

    @Test
    void theJqPipeGetsJsonAloneAndPrintsWhatThePageShows(@TempDir Path dir) throws Exception {
        List<Session> piped = sessions(dir).stream().filter(s -> !s.jq().isEmpty()).toList();
        assertEquals(1, piped.size(), "one session pipes into jq");
        Session s = piped.get(0);
        CommandRun r = CommandRun.of(s.args().toArray(String[]::new));
        assertEquals(2, r.exit(), "a query does not hold: " + r.err());
        // standard output is JSON alone, one trace a line, whether or not jq is here to read it
        List<String> json = r.out().lines().toList();
        assertEquals(2, json.size(), r.out());
        for (String line : json) {
            Map<?, ?> trace = assertInstanceOf(Map.class, Json.parse(line), line);
            assertTrue(trace.containsKey("states") && trace.containsKey("concrete"), line);
        }
        Tools.require(onPath("jq"), "jq (the page's jq filter)");
        Path input = dir.resolve("stdout.json");
        Files.writeString(input, r.out());
        Process jq = new ProcessBuilder(s.jq()).redirectInput(input.toFile()).redirectErrorStream(true).start();
        assertTrue(jq.waitFor(60, TimeUnit.SECONDS), "jq ends");
        String jqOut = new String(jq.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        assertEquals(0, jq.exitValue(), jqOut);
        match(s, ShellWords.lines(jqOut, dir), ShellWords.lines(r.err(), dir));
    }

    /** The page's verify sessions, with the page's model written to {@code dir} and the shared models found. */
    private static List<Session> sessions(Path dir) throws IOException {
        DocPage page = DocPage.read("verify.md");
        DocPage.Block model = page.blockAfter("On `crossing.xta`, a train and a gate");
        assertEquals("xta", model.info(), "the page's model");
        Files.writeString(dir.resolve("crossing.xta"), model.code());
        List<Session> sessions = new ArrayList<>();
        for (DocPage.Block b : page.blocksStartingWith(COMMAND)) {
            List<String> lines = new ArrayList<>(b.code().lines().toList());
            StringBuilder command = new StringBuilder();
            while (lines.get(0).endsWith("\\")) {
                String l = lines.remove(0);
                command.append(l, 0, l.length() - 1).append(' ');
            }
            command.append(lines.remove(0));
            List<String> words = ShellWords.split(command.substring(COMMAND.length()));
            Path file = dir.resolve(words.get(0));
            if (!Files.exists(file)) {
                file = SHARED.resolve("uppaal-examples").resolve(words.get(0));
            }
            if (!Files.exists(file)) {
                continue; // a model the page only describes (port.xta)
            }
            List<String> args = new ArrayList<>(List.of("verify", file.toString()));
            boolean dropErr = false;
            List<String> jq = List.of();
            for (int i = 1; i < words.size(); i++) {
                if (words.get(i).equals("2>/dev/null")) {
                    dropErr = true;
                } else if (words.get(i).equals("|")) {
                    jq = words.subList(i + 1, words.size());
                    assertEquals("jq", jq.get(0), b.code());
                    break;
                } else {
                    args.add(words.get(i));
                }
            }
            if (!file.startsWith(dir)) {
                // the page names the shared model as if it were in the current folder
                args.set(1, Files.copy(file, dir.resolve(file.getFileName())).toString());
            }
            sessions.add(new Session(args, dropErr, jq, lines, b.line()));
        }
        return sessions;
    }

    /**
     * Every line of the session, but {@code ...}, is a line of standard output or of standard error, each stream's
     * lines in their order.
     */
    private static void match(Session s, List<String> out, List<String> err) {
        int o = 0;
        int e = 0;
        for (String expected : s.expected()) {
            if (expected.strip().equals("...")) {
                continue;
            }
            Pattern p = pattern(expected);
            int atOut = find(p, out, o);
            int atErr = atOut >= 0 ? -1 : find(p, err, e);
            if (atOut >= 0) {
                o = atOut + 1;
            } else if (atErr >= 0) {
                e = atErr + 1;
            } else {
                fail("verify.md, the session on line " + s.line() + ": '" + expected + "' was not printed (after what"
                        + " the lines before it matched)\nstandard output:\n" + String.join("\n", out)
                        + "\nstandard error:\n" + String.join("\n", err));
            }
        }
    }

    private static int find(Pattern p, List<String> lines, int from) {
        for (int i = from; i < lines.size(); i++) {
            if (p.matcher(FIGURES.matcher(lines.get(i)).replaceAll("T")).matches()) {
                return i;
            }
        }
        return -1;
    }

    /** A session line as a pattern: "..." is any text, the time and memory of figures any figures. */
    private static Pattern pattern(String expected) {
        String[] parts = FIGURES.matcher(expected).replaceAll("T").split(Pattern.quote("..."), -1);
        StringBuilder regex = new StringBuilder();
        for (int i = 0; i < parts.length; i++) {
            regex.append(i == 0 ? "" : ".*").append(Pattern.quote(parts[i]));
        }
        return Pattern.compile(regex.toString());
    }

    private static boolean onPath(String tool) {
        String path = System.getenv("PATH");
        if (path == null) {
            return false;
        }
        for (String d : path.split(File.pathSeparator)) {
            if (Files.isExecutable(Path.of(d, tool))) {
                return true;
            }
        }
        return false;
    }
}
