package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.dtron.model.delta.DeltaExtension.Delay;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;

class DeltaReportTest {
    @Test
    void readsTheReportOfARun() throws Exception {
        DeltaReport r = DeltaReport.parse(Files.readString(Path.of(DeltaReportTest.class
                .getResource("delta-report.json").toURI())));
        assertEquals(new DeltaReport("ticker.xml", 10000, "3f2a9c", List.of(
                new DeltaReport.Channel("reset", true, 11, 180, 2400),
                new DeltaReport.Channel("tick", false, 24, 90, 1750))), r);
        assertEquals(Map.of("reset", new Delay(180, 2400), "tick", new Delay(90, 1750)), r.measured());
    }

    @Test
    void skipsUnmeasuredChannelsAndToleratesMissingNamesAndNewKeys() {
        DeltaReport r = DeltaReport.parse("{\"timeUnitMicros\": 1000, \"p99\": 3, \"channels\": ["
                + "{\"channel\": \"a\", \"direction\": \"input\", \"count\": 0, \"lowMicros\": 0, \"highMicros\": 0},"
                + "{\"channel\": \"b\", \"direction\": \"output\", \"count\": 2, \"lowMicros\": 5,"
                + " \"highMicros\": 9}]}");
        assertEquals(null, r.model());
        assertEquals(Map.of("b", new Delay(5, 9)), r.measured());
    }

    @Test
    void refusesOtherShapes() {
        assertEquals("the report is not a JSON object", message("[]"));
        assertEquals("the report: \"timeUnitMicros\" must be an integer, and is missing",
                message("{\"channels\": []}"));
        assertEquals("timeUnitMicros must be positive, not 0", message("{\"timeUnitMicros\": 0, \"channels\": []}"));
        assertEquals("the report has no \"channels\" array", message("{\"timeUnitMicros\": 10}"));
        assertEquals("channel 'a': needs count >= 0 and, when measured, 0 <= lowMicros <= highMicros, not count 1,"
                + " 5..4", message("{\"timeUnitMicros\": 10, \"channels\": [{\"channel\": \"a\", \"direction\":"
                + " \"input\", \"count\": 1, \"lowMicros\": 5, \"highMicros\": 4}]}"));
        assertEquals("channel 'a': \"lowMicros\" must be an integer", message("{\"timeUnitMicros\": 10, \"channels\":"
                + " [{\"channel\": \"a\", \"direction\": \"input\", \"count\": 1, \"lowMicros\": 1.5, \"highMicros\":"
                + " 4}]}"));
        assertEquals("channels[1]: channel 'a' appears twice", message("{\"timeUnitMicros\": 10, \"channels\": ["
                + "{\"channel\": \"a\", \"direction\": \"input\", \"count\": 0, \"lowMicros\": 0, \"highMicros\": 0},"
                + "{\"channel\": \"a\", \"direction\": \"input\", \"count\": 0, \"lowMicros\": 0,"
                + " \"highMicros\": 0}]}"));
        assertEquals("the report: \"runId\" must be a string", message("{\"timeUnitMicros\": 10, \"runId\": 7,"
                + " \"channels\": []}"));
    }

    private static String message(String json) {
        return assertThrows(IllegalArgumentException.class, () -> DeltaReport.parse(json)).getMessage();
    }
}
