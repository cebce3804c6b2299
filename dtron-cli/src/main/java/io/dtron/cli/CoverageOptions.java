package io.dtron.cli;

import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestResult;
import io.dtron.engine.coverage.Coverage;
import io.dtron.engine.coverage.Goals;
import io.dtron.engine.coverage.StopCondition;
import io.dtron.engine.coverage.Traps;
import io.dtron.model.Network;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import picocli.CommandLine.Option;

/**
 * The coverage options of {@code dtron run}: the coverage file, the stop condition, the trap variables and the
 * budget of the check of what can be covered; the summary line after the verdict.
 */
final class CoverageOptions {
    @Option(names = "--coverage", paramLabel = "FILE.json",
            description = "Write what the run covered (locations, edges, traps, channels and their values) as JSON"
                    + " to FILE; merge such files with dtron coverage merge.")
    Path file;

    @Option(names = "--until", paramLabel = "EXPR",
            description = "End the run PASSED when EXPR holds: edge_coverage(P), location_coverage(P),"
                    + " trap_coverage(P), reached(N), time(T), inputs(N), combined with and, or and parentheses;"
                    + " the timeout stays the outer bound.")
    String until;

    @Option(names = "--traps", split = ",", paramLabel = "NAME",
            description = "Count these bool variables or arrays as traps too (besides those named trap... or t_...).")
    List<String> traps = new ArrayList<>();

    @Option(names = "--coverage-budget", paramLabel = "MS", defaultValue = "2000",
            description = "How long the model checker may look for what can be covered before the run, in ms"
                    + " (default: ${DEFAULT-VALUE}; 0: no check, everything counts as coverable).")
    long budgetMillis;

    /**
     * Checks the options against {@code network} and {@code goals} before the run.
     *
     * @throws IllegalArgumentException with a message for the user, starting with the option at fault
     */
    void check(Network network, Goals goals) {
        if (budgetMillis < 0) {
            throw new IllegalArgumentException("--coverage-budget must not be negative");
        }
        List<String> trapNames;
        try {
            trapNames = Traps.of(network, traps);
        } catch (IllegalArgumentException e) {
            throw new IllegalArgumentException("--traps: " + e.getMessage());
        }
        if (until != null) {
            try {
                StopCondition.parse(until).check(goals.count(), trapNames.size());
            } catch (IllegalArgumentException e) {
                throw new IllegalArgumentException("--until '" + until + "': " + e.getMessage());
            }
        }
    }

    /** Sets {@code tester} up: traps, budget and stop condition (asking {@code goals}), as {@link #check}ed. */
    void configure(OnlineTester tester, Goals goals) {
        tester.traps(traps).coverableBudget(Duration.ofMillis(budgetMillis));
        if (until != null) {
            tester.until(StopCondition.parse(until), goals);
        }
    }

    /**
     * Prints the coverage summary of {@code result} and writes the coverage file when one was asked for; a file that
     * cannot be written is said on {@code err}.
     */
    void report(TestResult result, PrintWriter out, PrintWriter err) {
        Coverage c = result.coverage();
        if (c == null) {
            return;
        }
        out.println(c.summary());
        out.flush();
        if (file != null) {
            try {
                Files.writeString(file, CoverageJson.write(c), StandardCharsets.UTF_8);
            } catch (IOException e) {
                err.println("dtron run: cannot write the coverage file " + file + ": " + OutputFile.reason(e));
                err.flush();
            }
        }
    }
}
