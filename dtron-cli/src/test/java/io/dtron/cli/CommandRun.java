package io.dtron.cli;

import java.io.PrintWriter;
import java.io.StringWriter;

/**
 * A {@code dtron} command run in this JVM, as the tests run it: its exit code and what it printed on standard output
 * and standard error.
 */
public record CommandRun(int exit, String out, String err) {

    /** Runs {@code dtron ARGS...} and keeps what it printed. */
    public static CommandRun of(String... args) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int exit = DtronCommand.run(args, new PrintWriter(out, true), new PrintWriter(err, true));
        return new CommandRun(exit, out.toString(), err.toString());
    }
}
