package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.w3c.dom.Element;

/**
 * {@code dtron monitor --replay TRACE --junit FILE.xml} read back as the tools read it (a DOM parser that refuses
 * DOCTYPEs), on logs of the monitor tests' server model: a correct log one passing case, a log with a response too
 * early a failure with its first violation, a log with a line that cannot be read an error; the counts as properties.
 */
class MonitorJunitTest {
    /** A server answering 1.5 units after each request: all as the model allows. */
    private static final List<String> CORRECT = List.of("t_us,channel,values", "1000,req,n=4", "2500,resp,n=5",
            "6000,req,n=8", "7500,resp,n=9");
    /** The second response half a unit after its request, the fourth one too. */
    private static final List<String> EARLY = List.of("t_us,channel,values", "1000,req,n=4", "2500,resp,n=5",
            "6000,req,n=8", "6500,resp,n=9", "9000,req,n=2", "9500,resp,n=3");

    @TempDir
    Path dir;

    private static Element parse(Path xml) throws Exception {
        return JunitReportTest.parse(xml).getDocumentElement();
    }

    private static Map<String, String> properties(Element suite) {
        return JunitReportTest.properties(suite);
    }

    @Test
    void aCorrectLogIsOnePassingCaseWithTheCountsAsProperties() throws Exception {
        Path xml = dir.resolve("ok.xml");
        CommandRun r = MonitorCommandTest.monitor(dir, "ok.csv", CORRECT, MonitorCommandTest.SERVER.toString(),
                "--junit", xml.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        Element suite = parse(xml);
        assertEquals("dtron monitor " + MonitorCommandTest.SERVER, suite.getAttribute("name"));
        assertEquals(List.of("1", "0", "0"), JunitPageIT.counts(suite));
        Element test = (Element) suite.getElementsByTagName("testcase").item(0);
        assertEquals("replay of " + dir.resolve("ok.csv"), test.getAttribute("name"));
        assertEquals("dtron.monitor.server", test.getAttribute("classname"));
        assertEquals(0, test.getChildNodes().getLength(), "no failure, error or skipped in a passing case");
        Map<String, String> p = properties(suite);
        assertEquals("4", p.get("events"));
        assertEquals("0", p.get("violations"));
        assertEquals("0", p.get("rejected_lines"));
        assertEquals("csv", p.get("format"));
        assertEquals("initial", p.get("from"));
        assertTrue(suite.getElementsByTagName("system-out").item(0).getTextContent()
                .startsWith("dtron monitor: no violation, 4 events checked, 0 lines rejected, in "), r.out());
    }

    @Test
    void aViolationIsAFailureWithTheFirstOneAndTheirNumber() throws Exception {
        Path xml = dir.resolve("early.xml");
        CommandRun r = MonitorCommandTest.monitor(dir, "early.csv", EARLY, MonitorCommandTest.SERVER.toString(),
                "--continue", "--junit", xml.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        Element suite = parse(xml);
        String message = JunitReportTest.onlyFailure(suite, "VIOLATION");
        assertTrue(message.startsWith("violation 1 at t=6.500: resp(n=9) at t=6.500 is not allowed then"), message);
        assertTrue(message.endsWith(" (2 violations in all)"), message);
        assertTrue(r.out().contains("violation 1 at t=6.500: resp(n=9) at t=6.500 is not allowed then"), r.out());
        assertEquals("2", properties(suite).get("violations"));
        assertEquals("true", properties(suite).get("continue"));
    }

    @Test
    void aRejectedLineIsAnErrorNamingIt() throws Exception {
        Path xml = dir.resolve("bad.xml");
        List<String> lines = new java.util.ArrayList<>(CORRECT);
        lines.add(3, "3000,resp,n=many");
        CommandRun r = MonitorCommandTest.monitor(dir, "bad.csv", lines, MonitorCommandTest.SERVER.toString(),
                "--junit", xml.toString());
        assertEquals(3, r.exit(), r.out() + r.err());
        Element suite = parse(xml);
        assertEquals(List.of("1", "0", "1"), JunitPageIT.counts(suite));
        Element error = (Element) suite.getElementsByTagName("error").item(0);
        assertEquals("INCOMPLETE", error.getAttribute("type"));
        assertEquals("1 line of the trace rejected, the first 4: value of 'n' is not a 32-bit integer: many",
                error.getAttribute("message"));
    }

    @Test
    void aFolderThatDoesNotExistIsAUsageError() throws Exception {
        CommandRun r = MonitorCommandTest.monitor(dir, "ok.csv", CORRECT, MonitorCommandTest.SERVER.toString(),
                "--junit", dir.resolve("none/report.xml").toString());
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.err().contains("--junit " + dir.resolve("none/report.xml") + ": the folder "), r.err());
    }
}
