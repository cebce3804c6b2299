package io.dtron.cli;

import io.dtron.engine.monitor.Alarm;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;

/**
 * {@code dtron monitor --junit FILE.xml}: what the monitor judged as a JUnit XML report ({@link JunitXml}), one test
 * case per replay or per run watched on the bus. A run with a violation is a {@code failure} with its first
 * violation, one judged without all the evidence (lines of the trace rejected, messages too late to judge) an {@code
 * error}, and the others pass.
 */
final class MonitorJunit {
    private MonitorJunit() {
    }

    /**
     * The case {@code name} of a replay or a run: {@code violations} and the {@code first} of them (null if not
     * seen), with times in units of {@code unitMicros}; {@code missing} says what evidence was missing (null: none).
     */
    static JunitXml.Case runCase(String name, int violations, Alarm first, long unitMicros, String missing) {
        if (violations > 0) {
            String what = first == null ? violations + " violations"
                    : "violation " + first.number() + " at t=" + MonitorCommand.units(first.micros(), unitMicros) + ": "
                            + first.explanation() + (violations > 1 ? " (" + violations + " violations in all)" : "");
            return new JunitXml.Case(name, "failure", "VIOLATION", what);
        }
        if (missing != null) {
            return new JunitXml.Case(name, "error", "INCOMPLETE", missing);
        }
        return new JunitXml.Case(name, null, null, "no violation");
    }

    /**
     * Writes the report of {@code model} to {@code file}; returns false, having said why on {@code err}, if it
     * cannot be written.
     */
    static boolean write(Path file, Path model, List<JunitXml.Case> cases, Map<String, String> properties,
            double seconds, String summary, PrintWriter err) {
        try {
            JunitXml.write(file, "dtron monitor " + model, JunitXml.className("dtron.monitor.", model), cases,
                    properties, seconds, summary);
            return true;
        } catch (IOException e) {
            err.println("dtron monitor: cannot write " + file + ": " + e.getMessage());
            return false;
        }
    }
}
