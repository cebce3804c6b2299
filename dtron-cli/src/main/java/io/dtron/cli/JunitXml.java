package io.dtron.cli;

import io.dtron.engine.GoalStatus;
import io.dtron.engine.SteeringReport;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.engine.coverage.Coverage;
import java.io.IOException;
import java.io.OutputStream;
import java.io.PrintWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Instant;
import java.time.ZoneOffset;
import java.time.format.DateTimeFormatter;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import javax.xml.stream.XMLOutputFactory;
import javax.xml.stream.XMLStreamException;
import javax.xml.stream.XMLStreamWriter;

/**
 * {@code --junit FILE.xml}: a run (or a mutation analysis) as a JUnit XML report, in the form Surefire writes and
 * Jenkins, GitLab and Surefire's report plugin read: one {@code testsuite}; for {@code dtron run} one {@code testcase}
 * per run, or per goal when the run has goals, named by the seed (and the goal). A FAILED run is a {@code failure}
 * with the explanation, an INCONCLUSIVE one (or a goal not reached) an {@code error} with the reason, but a goal not
 * reached by a run that a stop condition ended PASSED is {@code skipped}, as the exit code is 0. The seed, the
 * settings, the coverage figures and the goals that were not reached are the suite's {@code properties}.
 */
final class JunitXml {
    private JunitXml() {
    }

    /**
     * One test case: its name, and null for a pass, else the element ({@code failure}, {@code error} or {@code
     * skipped}) and why; {@code type} names the outcome in the element's {@code type}; {@code seconds} of wall-clock
     * time it took, or negative for the whole report's.
     */
    record Case(String name, String problem, String type, String message, double seconds) {
        /** A case that took the whole report's time. */
        Case(String name, String problem, String type, String message) {
            this(name, problem, type, message, -1);
        }

        /** A case of a run's verdict: FAILED a failure, INCONCLUSIVE an error. */
        Case(String name, String problem, String message) {
            this(name, problem, "failure".equals(problem) ? "FAILED" : "INCONCLUSIVE", message);
        }

        /** This case, taking {@code s} seconds. */
        Case took(double s) {
            return new Case(name, problem, type, message, s);
        }
    }

    /**
     * The test cases of a run against {@code against}: one per goal of {@code steering} (null without goals), else
     * one for the run.
     */
    static List<Case> cases(TestResult result, String against, SteeringReport steering, long unitMicros) {
        String run = against + ", seed " + result.seed();
        List<Case> cases = new ArrayList<>();
        if (steering == null || steering.goals().isEmpty()) {
            cases.add(new Case(run, problem(result.verdict()), result.explanation()));
            return cases;
        }
        for (GoalStatus goal : steering.goals()) {
            String name = run + ", goal " + goal.text();
            if (result.verdict() == Verdict.FAILED) {
                cases.add(new Case(name, "failure", result.explanation()));
            } else if (goal.state() == GoalStatus.State.REACHED) {
                cases.add(new Case(name, null, "reached at t=" + GoalOptions.units(goal.micros(), unitMicros)));
            } else if (goal.state() == GoalStatus.State.UNREACHABLE) {
                cases.add(new Case(name, "error", "the goal can no longer be reached" + (goal.micros() < 0 ? ""
                        : " (from t=" + GoalOptions.units(goal.micros(), unitMicros) + ")") + ": " + goal.reason()));
            } else if (result.verdict() == Verdict.PASSED) {
                // a run whose goals decide ends INCONCLUSIVE with a goal open: this one's stop condition decided
                cases.add(new Case(name, "skipped", "PASSED", "the goal was not reached, and the stop condition"
                        + " decided the run: PASSED: " + result.explanation()));
            } else {
                cases.add(new Case(name, "error", "the goal was not reached: the run ended " + result.verdict() + ": "
                        + result.explanation()));
            }
        }
        return cases;
    }

    private static String problem(Verdict verdict) {
        return switch (verdict) {
            case PASSED -> null;
            case FAILED -> "failure";
            case INCONCLUSIVE -> "error";
        };
    }

    /** The suite's properties: the run's settings and result, the coverage figures and the goals not reached. */
    static Map<String, String> properties(String model, String against, TestResult result, long unitMicros,
                                          long timeout, boolean virtualTime, SteeringReport steering) {
        Map<String, String> p = new LinkedHashMap<>();
        p.put("model", model);
        p.put("system", against);
        p.put("seed", Long.toString(result.seed()));
        p.put("verdict", result.verdict().name());
        p.put("timeunit_us", Long.toString(unitMicros));
        p.put("timeout", Long.toString(timeout));
        p.put("virtual_time", Boolean.toString(virtualTime));
        p.put("inputs", Integer.toString(result.inputs()));
        p.put("outputs", Integer.toString(result.outputs()));
        p.put("duration_us", Long.toString(result.durationMicros()));
        Coverage coverage = result.coverage();
        if (coverage != null) {
            p.put("coverage.locations", coverage.locations().toString());
            p.put("coverage.edges", coverage.edges().toString());
            p.put("coverage.edges.environment", coverage.edges(true).toString());
            p.put("coverage.edges.implementation", coverage.edges(false).toString());
            if (coverage.trapFigure().total() > 0) {
                p.put("coverage.traps", coverage.trapFigure().toString());
            }
        }
        if (steering != null && !steering.goals().isEmpty()) {
            List<String> unmet = new ArrayList<>();
            for (int i = 0; i < steering.goals().size(); i++) {
                GoalStatus g = steering.goals().get(i);
                p.put("goal." + (i + 1), g.text() + ": " + g.state().name().toLowerCase(Locale.ROOT));
                if (g.state() != GoalStatus.State.REACHED) {
                    unmet.add(g.text());
                }
            }
            p.put("goals.unmet", String.join("; ", unmet));
        }
        return p;
    }

    /**
     * Writes the report: suite {@code suite}, its cases in class {@code className}, the properties, {@code seconds}
     * of wall-clock time, and {@code output} (what the run printed) as the suite's {@code system-out}.
     *
     * @throws IOException if the file cannot be written
     */
    static void write(Path file, String suite, String className, List<Case> cases, Map<String, String> properties,
                      double seconds, String output) throws IOException {
        long failures = cases.stream().filter(c -> "failure".equals(c.problem())).count();
        long errors = cases.stream().filter(c -> "error".equals(c.problem())).count();
        long skipped = cases.stream().filter(c -> "skipped".equals(c.problem())).count();
        String time = String.format(Locale.ROOT, "%.3f", seconds);
        try (OutputStream stream = Files.newOutputStream(file)) {
            XMLStreamWriter xml = XMLOutputFactory.newFactory().createXMLStreamWriter(stream, "UTF-8");
            xml.writeStartDocument("UTF-8", "1.0");
            xml.writeCharacters("\n");
            xml.writeStartElement("testsuite");
            xml.writeAttribute("name", clean(suite));
            xml.writeAttribute("tests", Integer.toString(cases.size()));
            xml.writeAttribute("failures", Long.toString(failures));
            xml.writeAttribute("errors", Long.toString(errors));
            xml.writeAttribute("skipped", Long.toString(skipped));
            xml.writeAttribute("time", time);
            xml.writeAttribute("timestamp", DateTimeFormatter.ISO_LOCAL_DATE_TIME.format(
                    Instant.now().atOffset(ZoneOffset.UTC).withNano(0)));
            xml.writeCharacters("\n  ");
            xml.writeStartElement("properties");
            for (Map.Entry<String, String> p : properties.entrySet()) {
                xml.writeCharacters("\n    ");
                xml.writeEmptyElement("property");
                xml.writeAttribute("name", clean(p.getKey()));
                xml.writeAttribute("value", clean(p.getValue()));
            }
            xml.writeCharacters("\n  ");
            xml.writeEndElement();
            for (Case c : cases) {
                xml.writeCharacters("\n  ");
                xml.writeStartElement("testcase");
                xml.writeAttribute("name", clean(c.name()));
                xml.writeAttribute("classname", clean(className));
                xml.writeAttribute("time", c.seconds() < 0 ? time : String.format(Locale.ROOT, "%.3f",
                        c.seconds()));
                if (c.problem() != null) {
                    xml.writeCharacters("\n    ");
                    xml.writeStartElement(c.problem());
                    xml.writeAttribute("message", clean(c.message()));
                    xml.writeAttribute("type", clean(c.type()));
                    xml.writeCharacters(clean(c.message()));
                    xml.writeEndElement();
                    xml.writeCharacters("\n  ");
                }
                xml.writeEndElement();
            }
            xml.writeCharacters("\n  ");
            xml.writeStartElement("system-out");
            xml.writeCharacters(clean(output));
            xml.writeEndElement();
            xml.writeCharacters("\n");
            xml.writeEndElement();
            xml.writeCharacters("\n");
            xml.writeEndDocument();
            xml.close();
        } catch (XMLStreamException e) {
            // the writer's own failure (a full disk) is the IOException it wraps
            throw e.getNestedException() instanceof IOException io ? io : new IOException(e.getMessage(), e);
        }
    }

    /**
     * Writes the report of {@code dtron COMMAND MODEL} as {@link #write} does (suite {@code dtron COMMAND MODEL}, class
     * {@code dtron.COMMAND.} and the model's name); returns false, having said why on {@code err}, if the file cannot
     * be written.
     */
    static boolean writeOrSay(Path file, String command, Path model, List<Case> cases, Map<String, String> properties,
            double seconds, String output, PrintWriter err) {
        try {
            write(file, "dtron " + command + " " + model, className("dtron." + command + ".", model), cases, properties,
                    seconds, output);
            return true;
        } catch (IOException e) {
            err.println("dtron " + command + ": cannot write " + file + ": " + OutputFile.reason(e));
            return false;
        }
    }

    /** The class name of the test cases of {@code model}: {@code prefix} and the file's name without extension. */
    static String className(String prefix, Path model) {
        String name = model.getFileName().toString();
        return prefix + (name.contains(".") ? name.substring(0, name.lastIndexOf('.')) : name);
    }

    /** {@code text} without the characters XML 1.0 cannot hold (control characters but tab and line ends). */
    static String clean(String text) {
        StringBuilder sb = new StringBuilder(text.length());
        text.codePoints().forEach(c -> {
            boolean allowed = c == '\t' || c == '\n' || c == '\r' || c >= 0x20 && c <= 0xd7ff
                    || c >= 0xe000 && c <= 0xfffd || c >= 0x10000 && c <= 0x10ffff;
            sb.appendCodePoint(allowed ? c : 0xfffd);
        });
        return sb.toString();
    }
}
