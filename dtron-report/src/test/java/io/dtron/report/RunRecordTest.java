package io.dtron.report;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;

/** The page's data: what a run recorded, as JSON the page's script reads, safe inside the page. */
class RunRecordTest {

    @Test
    void textFromTheRunCannotEndThePagesScript() throws Exception {
        RunRecord record = new RunRecord("<b>model</b>.xml", null, null, null);
        record.event(false, 10, "a</script><script>alert(1)</script>", Map.of("x", 1));
        record.verdict("FAILED", "output </script> observed & more", 10, 0, 1);
        String page = ReportPage.html(record);
        int scripts = page.split("</script>", -1).length - 1;
        assertEquals(2, scripts, "the page's own two scripts end, nothing else does");
        assertFalse(page.contains("<b>model"), "markup in the data is escaped");
        assertTrue(page.contains("\\u003c/script\\u003e"), "escaped as \\u003c");
    }

    @Test
    void theTestersEdgesAreFoundInTheModelByTheirLocationsAndLabel() throws Exception {
        RunRecord record = LampRuns.record();
        // the lamp's user goes from busy to idle on two edges, both release! (their guards differ): a name the
        // tester gives matches both
        record.edges(5, List.of("user: idle -> busy grasp!", "user: busy -> idle release!"), List.of());
        String json = record.json();
        var user = LampRuns.network().process("user").orElseThrow();
        List<Integer> grasp = new java.util.ArrayList<>();
        List<Integer> release = new java.util.ArrayList<>();
        for (var e : user.edges()) {
            String from = user.locations().get(e.source()).name();
            String to = user.locations().get(e.target()).name();
            if (from.equals("idle") && to.equals("busy")) {
                grasp.add(e.index());
            } else if (from.equals("busy") && to.equals("idle")) {
                release.add(e.index());
            }
        }
        assertEquals(1, grasp.size());
        assertEquals(2, release.size());
        int p = user.index();
        assertTrue(json.contains("\"edges\":[[5,[" + p + "," + grasp.get(0) + "," + p + "," + release.get(0) + ","
                + p + "," + release.get(1) + "],[]]]"), json.substring(json.indexOf("\"edges\":[[")));
    }

    @Test
    void aRunRecordsEveryEventWithItsTimeAndTheVerdict() throws Exception {
        RunRecord record = LampRuns.record();
        TestResult result = LampRuns.run(record, 7, 5000);
        assertEquals(Verdict.PASSED, result.verdict(), result.explanation());
        assertEquals(result.inputs() + result.outputs(), record.eventCount());
        String json = record.json();
        assertTrue(json.startsWith("{\"report\":1,"), json.substring(0, 40));
        assertTrue(json.contains("\"verdict\":{\"verdict\":\"PASSED\""), "the verdict");
        assertTrue(json.contains("\"coverage\":{\"summary\":"), "the coverage");
        // every output the lamp's model requires by a deadline carries it, after the output's own time, and every
        // output of the run that passed, the window the model allowed it in, around its time
        java.util.regex.Matcher m = java.util.regex.Pattern.compile(
                "\\[1,(\\d+),\"level\",\"[^\"]*\",(-?\\d+),(-?\\d+),(-?\\d+)\\]").matcher(json);
        int outputs = 0;
        while (m.find()) {
            outputs++;
            long at = Long.parseLong(m.group(1));
            long due = Long.parseLong(m.group(2));
            long from = Long.parseLong(m.group(3));
            long until = Long.parseLong(m.group(4));
            assertTrue(due == -1 || due >= at, m.group());
            assertTrue(from >= 0 && from <= at && (until == -1 || until >= at), m.group());
        }
        assertEquals(result.outputs(), outputs);
    }

    @Test
    void anOutputCarriesTheWindowGivenBeforeItAndOnlyIt() {
        RunRecord record = new RunRecord("ticker.xta", null, null, null);
        record.window(8_000, 12_000);
        record.event(false, 10_000, "tick", Map.of());
        record.event(true, 11_000, "reset", Map.of());
        record.event(false, 21_000, "tick", Map.of());
        record.window(29_000, -1);
        record.event(false, 30_000, "tick", Map.of());
        String json = record.json();
        assertTrue(json.contains("[1,10000,\"tick\",\"\",-1,8000,12000],\n[0,11000,\"reset\",\"\",-1,-1,-1],\n"
                + "[1,21000,\"tick\",\"\",-1,-1,-1],\n[1,30000,\"tick\",\"\",-1,29000,-1]"), json);
    }

    @Test
    void recordedEdgesNameProcessAndEdgeNumbers() throws Exception {
        RunRecord record = LampRuns.record();
        LampRuns.run(record, 3, 2000);
        String json = record.json();
        String edges = json.substring(json.indexOf("\"edges\":[["), json.indexOf("],\"verdict\""));
        assertFalse(edges.contains("[]],[]]"), "some edge was found");
    }
}
