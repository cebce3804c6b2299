package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;

import java.util.List;
import org.junit.jupiter.api.Test;

/** The trace reader's reading of DTRON's own lines without the general JSON parser. */
class TraceLineTest {
    @Test
    void theLinesDtronWritesReadAsTheGeneralParserReadsThem() {
        for (String line : List.of(
                "{\"kind\":\"start\",\"timeunit_us\":1000,\"timeout\":300,\"seed\":-7}",
                "{\"kind\":\"input\",\"t_us\":100000,\"channel\":\"grasp\",\"values\":{}}",
                "{\"kind\":\"output\",\"t_us\":159448,\"channel\":\"level\",\"values\":{\"adapLevel\":0,\"b\":-12}}",
                "{\"t_us\":0,\"channel\":\"r\u00e9ponse\"}",
                "{\"kind\":\"truncated\",\"max_bytes\":100,\"omitted_lines\":3,\"after_t_us\":999999999999999999}",
                "{}")) {
            assertNotNull(TraceReader.Flat.parse(line), line);
            assertEquals(Json.parse(line), TraceReader.Flat.parse(line), line);
        }
    }

    @Test
    void everyOtherLineIsLeftToTheGeneralParser() {
        for (String line : List.of(
                "{\"t_us\": 1,\"channel\":\"a\"}", // a space
                "{\"t_us\":1.5,\"channel\":\"a\"}", // not an integer
                "{\"t_us\":1e3,\"channel\":\"a\"}",
                "{\"t_us\":01,\"channel\":\"a\"}", // a leading zero
                "{\"t_us\":1234567890123456789,\"channel\":\"a\"}", // more than 18 digits
                "{\"t_us\":-,\"channel\":\"a\"}",
                "{\"t_us\":1,\"channel\":\"a\\\"b\"}", // an escape
                "{\"t_us\":1,\"channel\":\"a\tb\"}", // a control character
                "{\"t_us\":1,\"t_us\":2}", // a key twice
                "{\"t_us\":1,\"values\":{\"a\":{}}}", // nested twice
                "{\"t_us\":1,\"ok\":true}",
                "{\"t_us\":1,\"list\":[1]}",
                "{\"t_us\":1}{}", // text after the object
                "{\"t_us\":1,}",
                "{\"t_us\":1",
                "[1]",
                "")) {
            assertNull(TraceReader.Flat.parse(line), line);
        }
    }
}
