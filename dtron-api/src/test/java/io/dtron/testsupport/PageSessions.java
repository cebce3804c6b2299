package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.assertFalse;

import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.function.UnaryOperator;

/**
 * The {@code $ java -jar dtron.jar ...} sessions of a site page, for the tests that run them as written: each
 * command (a line ending in {@code \} goes on on the next) with the lines the page shows it print, up to the next
 * command or the end of its block; and a run of one in this JVM, which prints no stack trace.
 */
public final class PageSessions {
    /** How a page's command line starts. */
    public static final String PROMPT = "$ java -jar dtron.jar ";

    private PageSessions() {
    }

    /**
     * One session of a page.
     *
     * @param line     the line of the page where its block starts
     * @param command  the command line, without the prompt
     * @param args     its words, each as the test mapped it (a file name to its path in the test's folder, say)
     * @param expected the lines the page shows it print
     */
    public record Session(int line, String command, List<String> args, List<String> expected) {
    }

    /** What a session printed, and its exit code. */
    public record Printed(int exit, String out, String err) {
    }

    /** The command: DTRON's command line, as {@code DtronCommand.run} runs it. */
    @FunctionalInterface
    public interface Command {
        /** Runs {@code args}, printing to {@code out} and {@code err}; returns the exit code. */
        int run(String[] args, PrintWriter out, PrintWriter err);
    }

    /** Every session of {@code page}, in its order, each word of a command mapped by {@code word}. */
    public static List<Session> of(DocPage page, UnaryOperator<String> word) {
        List<Session> sessions = new ArrayList<>();
        for (DocPage.Block b : page.blocksStartingWith(PROMPT)) {
            List<String> lines = b.code().lines().toList();
            for (int i = 0; i < lines.size(); ) {
                StringBuilder command = new StringBuilder();
                while (lines.get(i).endsWith("\\")) {
                    String l = lines.get(i++);
                    command.append(l, 0, l.length() - 1).append(' ');
                }
                command.append(lines.get(i++));
                List<String> expected = new ArrayList<>();
                while (i < lines.size() && !lines.get(i).startsWith(PROMPT)) {
                    expected.add(lines.get(i++));
                }
                String text = command.substring(PROMPT.length());
                sessions.add(new Session(b.line(), text, ShellWords.split(text).stream().map(word).toList(),
                        List.copyOf(expected)));
            }
        }
        return sessions;
    }

    /**
     * The words of sessions run in {@code folder}: a file name ending in one of {@code extensions} ("xml|trn", say)
     * names the file there, and {@code models/target/classes} that folder of the checkout at {@code root}.
     */
    public static UnaryOperator<String> inFolder(Path folder, String extensions, Path root) {
        return word -> word.matches("[\\w-]+\\.(" + extensions + ")") ? folder.resolve(word).toString()
                : word.equals("models/target/classes") ? root.resolve(word).toString() : word;
    }

    /** Runs a session's command in this JVM; what it prints to its error stream holds no stack trace. */
    public static Printed run(Command command, Session session) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int exit = command.run(session.args().toArray(String[]::new), new PrintWriter(out, true),
                new PrintWriter(err, true));
        assertFalse(err.toString().contains("\tat "), "no stack trace: " + err);
        return new Printed(exit, out.toString(), err.toString());
    }
}
