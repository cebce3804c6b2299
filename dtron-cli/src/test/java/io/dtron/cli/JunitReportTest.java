package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import javax.xml.parsers.DocumentBuilderFactory;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.w3c.dom.Document;
import org.w3c.dom.Element;
import org.w3c.dom.NodeList;

/**
 * {@code dtron run --junit FILE.xml} read back as the tools read it (a DOM parser that refuses DOCTYPEs): the test
 * cases by their names, FAILED as a failure with the explanation, INCONCLUSIVE as an error, the properties; and
 * {@code --trace-max-size}.
 */
class JunitReportTest {
    @TempDir
    Path dir;

    @Test
    void aPassedRunIsOneTestCaseNamedBySystemAndSeedWithTheSeedAndCoverageAsProperties() throws Exception {
        Path model = ticker("ticker.xta");
        Path xml = dir.resolve("run.xml");
        CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "7", "--timeout", "300", "--junit", xml.toString());
        assertEquals(0, r.exit(), r.out() + r.err());

        Element suite = parse(xml).getDocumentElement();
        assertEquals("testsuite", suite.getTagName());
        assertEquals("dtron run " + model, suite.getAttribute("name"));
        assertEquals(List.of("1", "0", "0"), List.of(suite.getAttribute("tests"), suite.getAttribute("failures"),
                suite.getAttribute("errors")));
        Element test = only(suite, "testcase");
        assertEquals(TickerForTests.class.getName() + ", seed 7", test.getAttribute("name"));
        assertEquals("dtron.ticker", test.getAttribute("classname"));
        assertTrue(Double.parseDouble(test.getAttribute("time")) >= 0);
        assertEquals(0, test.getElementsByTagName("failure").getLength() + test.getElementsByTagName("error")
                .getLength());
        Map<String, String> properties = properties(suite);
        assertEquals("7", properties.get("seed"));
        assertEquals("PASSED", properties.get("verdict"));
        assertEquals("300", properties.get("timeout"));
        assertTrue(properties.get("coverage.edges").matches("\\d+/\\d+ \\(\\d+\\.\\d%\\)"), properties.toString());
        assertTrue(properties.containsKey("coverage.locations"), properties.toString());
        assertFalse(properties.containsKey("goals.unmet"), "a run without goals has none unmet");
        assertTrue(suite.getElementsByTagName("system-out").item(0).getTextContent().startsWith("PASSED: the timeout"));
    }

    @Test
    void aFailedRunIsAFailureWithTheExplanation() throws Exception {
        Path xml = dir.resolve("failed.xml");
        CommandRun r = CommandRun.of("run", ticker("ticker.xta").toString(), "--sut",
                TickerForTests.class.getName() + ":slow", "--virtual-time", "--seed", "7", "--timeout", "300",
                "--junit", xml.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        String explanation = r.out().lines().filter(l -> l.startsWith("FAILED: ")).findFirst().orElseThrow()
                .substring("FAILED: ".length());

        Element suite = parse(xml).getDocumentElement();
        assertEquals(List.of("1", "1", "0"), List.of(suite.getAttribute("tests"), suite.getAttribute("failures"),
                suite.getAttribute("errors")));
        Element failure = only(only(suite, "testcase"), "failure");
        assertEquals(explanation, failure.getAttribute("message"));
        assertEquals(explanation, failure.getTextContent());
        assertEquals("FAILED", failure.getAttribute("type"));
        assertTrue(explanation.startsWith("no output came by t=12.000"), explanation);
        assertEquals("FAILED", properties(suite).get("verdict"));
    }

    @Test
    void aRunWithGoalsIsOneTestCasePerGoalAGoalNotReachedAnErrorAndUnmet() throws Exception {
        Path xml = dir.resolve("goals.xml");
        String reachable = "E<> o_tick_seq == 2";
        String unreachable = "E<> Ticker.x > 100";
        CommandRun r = CommandRun.of("run", ticker("ticker.xta").toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "3", "--timeout", "300", "--strategy", "goal", "--goal", reachable,
                "--goal", unreachable, "--junit", xml.toString());
        assertEquals(3, r.exit(), r.out() + r.err());

        Element suite = parse(xml).getDocumentElement();
        NodeList tests = suite.getElementsByTagName("testcase");
        assertEquals(2, tests.getLength());
        Element first = (Element) tests.item(0);
        Element second = (Element) tests.item(1);
        String run = TickerForTests.class.getName() + ", seed 3, goal ";
        assertEquals(run + reachable, first.getAttribute("name"));
        assertEquals(0, first.getElementsByTagName("*").getLength(),
                "the reached goal passes");
        assertEquals(run + unreachable, second.getAttribute("name"));
        Element error = only(second, "error");
        assertEquals("INCONCLUSIVE", error.getAttribute("type"));
        assertTrue(error.getAttribute("message").startsWith("the goal can no longer be reached: the model checker"
                + " finds no reachable state where it holds"), error.getAttribute("message"));
        assertEquals(List.of("2", "0", "1"), List.of(suite.getAttribute("tests"), suite.getAttribute("failures"),
                suite.getAttribute("errors")));
        Map<String, String> properties = properties(suite);
        assertEquals(unreachable, properties.get("goals.unmet"));
        assertEquals(reachable + ": reached", properties.get("goal.1"));
        assertEquals(unreachable + ": unreachable", properties.get("goal.2"));
    }

    @Test
    void aGoalNotReachedByTheTimeoutEndsTheRunInconclusiveAndTheExitCodeAndTheReportAgree() throws Exception {
        // the model lets the ticker count to 50, but ten ticks at most fit in 100 units
        String far = "E<> o_tick_seq == 50";
        Path xml = dir.resolve("open.xml");
        CommandRun r = CommandRun.of("run", ticker("ticker.xta").toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "3", "--timeout", "100", "--strategy", "goal", "--goal", far,
                "--junit", xml.toString());
        assertEquals(3, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("INCONCLUSIVE: the timeout of 100 time units was reached after "), r.out());
        assertTrue(r.out().contains(", but not every goal was reached, so the run did not serve its purpose: not"
                + " reached: '" + far + "'"), r.out());
        Element suite = parse(xml).getDocumentElement();
        assertEquals("INCONCLUSIVE", properties(suite).get("verdict"));
        Element error = only(only(suite, "testcase"), "error");
        assertTrue(error.getAttribute("message").startsWith("the goal was not reached: the run ended INCONCLUSIVE"),
                error.getAttribute("message"));

        // a stop condition decides instead of the goals: PASSED, exit code 0, and the goal's case skipped, no error
        Path until = dir.resolve("until.xml");
        CommandRun u = CommandRun.of("run", ticker("ticker.xta").toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "3", "--timeout", "100", "--strategy", "goal", "--goal", far,
                "--until", "reached(1) or time(50)", "--junit", until.toString());
        assertEquals(0, u.exit(), u.out() + u.err());
        Element passed = parse(until).getDocumentElement();
        assertEquals(List.of("1", "0", "0", "1"), List.of(passed.getAttribute("tests"),
                passed.getAttribute("failures"), passed.getAttribute("errors"), passed.getAttribute("skipped")));
        Element skipped = only(only(passed, "testcase"), "skipped");
        assertTrue(skipped.getAttribute("message").startsWith("the goal was not reached, and the stop condition decided"
                + " the run: PASSED: the stop condition reached(1) or time(50) was met"), skipped.getAttribute("message"));
    }

    @Test
    void namesWithMarkupAreEscapedAndReadBackAsTheyAre() throws Exception {
        Path model = ticker("tick<&\"'>er.xta");
        Path xml = dir.resolve("markup.xml");
        CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "1", "--timeout", "50", "--junit", xml.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        String text = Files.readString(xml);
        assertFalse(text.contains("<!DOCTYPE") || text.contains("<!ENTITY"), text);
        Element suite = parse(xml).getDocumentElement();
        assertEquals("dtron run " + model, suite.getAttribute("name"));
        assertEquals(model.toString(), properties(suite).get("model"));
    }

    @Test
    void theMutantsAreOneTestCaseEachAsTheirJsonSays() throws Exception {
        Path model = Files.writeString(dir.resolve("beeper.xta"), Files.readString(
                Path.of("../dtron-engine/src/test/resources/io/dtron/engine/sim/beeper.xta")));
        Path xml = dir.resolve("mutants.xml");
        Path json = dir.resolve("mutants.json");
        CommandRun r = CommandRun.of("mutants", model.toString(), "--budget", "100", "--seeds", "10", "--seed", "1",
                "--delay-policy", "eager", "--json", json.toString(), "--junit", xml.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        Map<?, ?> root = (Map<?, ?>) Json.parse(Files.readString(json));
        List<?> mutants = (List<?>) root.get("mutants");

        Element suite = parse(xml).getDocumentElement();
        NodeList tests = suite.getElementsByTagName("testcase");
        assertEquals(mutants.size() + 1, tests.getLength());
        Element model0 = (Element) tests.item(0);
        assertEquals("the model as its own system, seeds 1..10", model0.getAttribute("name"));
        assertEquals(0, model0.getElementsByTagName("*").getLength(), "the model passes with every seed");
        assertEquals(List.of(String.valueOf(mutants.size() + 1), String.valueOf(root.get("survived")), "0",
                String.valueOf(root.get("equivalent"))), List.of(suite.getAttribute("tests"),
                suite.getAttribute("failures"), suite.getAttribute("errors"), suite.getAttribute("skipped")));
        for (int i = 0; i < mutants.size(); i++) {
            Map<?, ?> m = (Map<?, ?>) mutants.get(i);
            Element test = (Element) tests.item(i + 1);
            assertTrue(test.getAttribute("name").startsWith("mutant " + m.get("number") + ": " + m.get("kind") + ", "
                    + m.get("change") + " (beeper.xta:"), test.getAttribute("name"));
            String element = switch (m.get("status").toString()) {
                case "killed" -> null;
                case "survived" -> "failure";
                default -> "skipped";
            };
            assertEquals(element == null ? 0 : 1, test.getElementsByTagName("*").getLength(),
                    test.getAttribute("name"));
            if (element != null) {
                Element problem = only(test, element);
                assertEquals(m.get("status").toString().toUpperCase(java.util.Locale.ROOT),
                        problem.getAttribute("type"));
            }
        }
        Map<String, String> properties = properties(suite);
        assertEquals(root.get("killed") + "/" + (((Long) root.get("killed")) + (Long) root.get("survived")),
                properties.get("mutation_score"));
        assertEquals("1..10", properties.get("seeds"));
    }

    @Test
    void aBadJunitFolderOrTraceSizeIsAUsageError() {
        String model = dir.resolve("none.xta").toString();
        CommandRun folder = CommandRun.of("run", model, "--sut", "x", "--junit",
                dir.resolve("no/such/r.xml").toString());
        assertEquals(1, folder.exit());
        assertTrue(folder.err().startsWith("dtron run: --junit " + dir.resolve("no/such/r.xml") + ": the folder "
                + dir.resolve("no/such") + " does not exist"), folder.err());
        CommandRun size = CommandRun.of("run", model, "--sut", "x", "--trace", "t.jsonl", "--trace-max-size", "10XB");
        assertEquals(1, size.exit());
        assertTrue(size.err().startsWith("dtron run: --trace-max-size 10XB: give a positive size in bytes, or with KB,"
                + " MB or GB (e.g. 10MB)"), size.err());
        CommandRun huge = CommandRun.of("run", model, "--sut", "x", "--trace", "t.jsonl", "--trace-max-size",
                "999999999999GB");
        assertEquals(1, huge.exit());
        assertTrue(huge.err().startsWith("dtron run: --trace-max-size 999999999999GB: give a positive size"),
                huge.err());
        CommandRun mutants = CommandRun.of("mutants", model, "--junit", dir.resolve("no/such/m.xml").toString());
        assertEquals(1, mutants.exit());
        assertTrue(mutants.err().startsWith("dtron mutants: --junit " + dir.resolve("no/such/m.xml") + ": the folder "),
                mutants.err());
        CommandRun alone = CommandRun.of("run", model, "--sut", "x", "--trace-max-size", "1MB");
        assertEquals(1, alone.exit());
        assertTrue(alone.err().startsWith("dtron run: --trace-max-size bounds the --trace file: give --trace FILE"
                + " too"), alone.err());
    }

    @Test
    void aBoundedTraceStopsAtItsBoundWithANoteAndEndsWithTheVerdict() throws Exception {
        Path trace = dir.resolve("trace.jsonl");
        CommandRun r = CommandRun.of("run", ticker("ticker.xta").toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "7", "--timeout", "100000", "--trace", trace.toString(),
                "--trace-max-size", "4KB");
        assertEquals(0, r.exit(), r.out() + r.err());
        List<String> lines = Files.readAllLines(trace);
        // the truncated line comes before the coverage and verdict lines, which end every trace
        String truncated = lines.get(lines.size() - 3);
        String coverage = lines.get(lines.size() - 2);
        String verdict = lines.get(lines.size() - 1);
        assertTrue(coverage.startsWith("{\"kind\":\"coverage\","), coverage);
        assertTrue(lines.get(0).startsWith("{\"kind\":\"start\",\"seed\":7,"), lines.get(0));
        assertTrue(verdict.startsWith("{\"kind\":\"verdict\",\"t_us\":100000000,\"verdict\":\"PASSED\""), verdict);
        assertTrue(truncated.startsWith("{\"kind\":\"truncated\",\"max_bytes\":4096,\"omitted_lines\":"), truncated);
        // the whole file keeps to the bound, the lines that end it included: the last events give way to them
        long size = Files.size(trace);
        assertTrue(size <= 4096 && size > 4096 - 400, "the trace fills its bound, less than a line and the room of"
                + " the truncated line: " + size);
        String lastEvent = lines.get(lines.size() - 4);
        java.util.regex.Matcher t = java.util.regex.Pattern.compile("\"t_us\":(\\d+),").matcher(lastEvent);
        assertTrue(t.find(), lastEvent);
        assertTrue(truncated.endsWith(",\"after_t_us\":" + t.group(1) + "}"), truncated + " after " + lastEvent);
        assertTrue(r.out().contains("dtron run: the trace " + trace + " stopped at its bound of 4096 bytes after the"
                + " event at t_us " + t.group(1) + ": "), r.out());
        assertTrue(r.out().indexOf("stopped at its bound") < r.out().indexOf("PASSED: "), r.out());
    }

    private Path ticker(String name) throws Exception {
        return Files.writeString(dir.resolve(name), RunCommandTest.TICKER);
    }

    /** Parses as a careful reader does: no DOCTYPE, no external entities. */
    static Document parse(Path xml) throws Exception {
        DocumentBuilderFactory factory = DocumentBuilderFactory.newInstance();
        factory.setFeature("http://apache.org/xml/features/disallow-doctype-decl", true);
        factory.setExpandEntityReferences(false);
        return factory.newDocumentBuilder().parse(xml.toFile());
    }

    private static Element only(Element parent, String tag) {
        NodeList list = parent.getElementsByTagName(tag);
        assertEquals(1, list.getLength(), "one <" + tag + "> in <" + parent.getTagName() + ">");
        return (Element) list.item(0);
    }

    /** The message of the one test case of a suite, a failure of {@code type}; asserts that it is that. */
    static String onlyFailure(Element suite, String type) {
        assertEquals(List.of("1", "1", "0"), JunitPageIT.counts(suite));
        Element failure = (Element) suite.getElementsByTagName("failure").item(0);
        assertEquals(type, failure.getAttribute("type"));
        return failure.getAttribute("message");
    }

    /** The suite's properties by name, in order. */
    static Map<String, String> properties(Element suite) {
        Map<String, String> map = new LinkedHashMap<>();
        NodeList list = suite.getElementsByTagName("property");
        for (int i = 0; i < list.getLength(); i++) {
            Element p = (Element) list.item(i);
            map.put(p.getAttribute("name"), p.getAttribute("value"));
        }
        return map;
    }
}
