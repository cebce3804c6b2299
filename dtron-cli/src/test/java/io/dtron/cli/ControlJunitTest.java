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
 * {@code dtron control --junit FILE.xml} read back as the tools read it, on the robot arm in virtual time: a run that
 * completes one passing case, the stalling plant (mutant 7) a failure with the alarm and the safe action; the
 * settings and counts as properties.
 */
class ControlJunitTest {
    @TempDir
    Path dir;

    @Test
    void aCompletedRunIsOnePassingCase() throws Exception {
        Path xml = dir.resolve("control.xml");
        CommandRun r = CommandRun.of("control", ControlCommandTest.ARM, "--plant", "model", "--virtual-time",
                "--duration", "100", "--seed", "1", "--safe-action", "i_stop", "--junit", xml.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        Element suite = JunitReportTest.parse(xml).getDocumentElement();
        assertEquals("dtron control " + ControlCommandTest.ARM, suite.getAttribute("name"));
        assertEquals(List.of("1", "0", "0"), JunitPageIT.counts(suite));
        Element test = (Element) suite.getElementsByTagName("testcase").item(0);
        assertEquals("control against the model's own plant part, seed 1", test.getAttribute("name"));
        assertEquals("dtron.control.robot-arm", test.getAttribute("classname"));
        Map<String, String> p = JunitReportTest.properties(suite);
        assertEquals("COMPLETED", p.get("outcome"));
        assertEquals("0", p.get("alarms"));
        assertTrue(r.out().contains(" " + p.get("commands") + " commands sent, " + p.get("readings") + " readings, 0"
                + " alarms (seed 1)"), r.out() + p);
    }

    @Test
    void anAlarmIsAFailureWithTheSafeActionTaken() throws Exception {
        Path xml = dir.resolve("stall.xml");
        CommandRun r = CommandRun.of("control", ControlCommandTest.ARM, "--plant", "model", "--plant-mutant", "7",
                "--virtual-time", "--duration", "100", "--seed", "1", "--safe-action", "i_stop", "--junit",
                xml.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        Element suite = JunitReportTest.parse(xml).getDocumentElement();
        String message = JunitReportTest.onlyFailure(suite, "ALARM");
        assertTrue(message.startsWith("ALARM at t=5.001: no reading came by t=5.000: "), message);
        assertTrue(message.endsWith("; safe action stop() taken"), message);
        Map<String, String> p = JunitReportTest.properties(suite);
        assertEquals("ALARM", p.get("outcome"));
        assertEquals("stop()", p.get("safe_action"));
        assertTrue(p.get("plant").startsWith("mutant 7 of the plant part"), p.toString());
    }

    @Test
    void aFolderThatDoesNotExistIsAUsageError() {
        CommandRun r = CommandRun.of("control", ControlCommandTest.ARM, "--plant", "model", "--virtual-time",
                "--duration", "10", "--junit", dir.resolve("none/control.xml").toString());
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.err().contains("--junit " + dir.resolve("none/control.xml") + ": the folder "), r.err());
    }
}
