package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.math.BigDecimal;
import java.util.Arrays;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;

class JsonTest {
    @Test
    void readsEveryKindOfValue() {
        Object v = Json.parse(" {\"a\": [1, -2.5e1, true, false, null], \"s\": \"q\\\"\\u00e9\\n\", \"o\": {}} ");
        assertEquals(Map.of("a", Arrays.asList(1L, new BigDecimal("-2.5e1"), true, false, null), "s", "q\"\u00e9\n",
                "o", Map.of()), v);
        assertEquals(List.of(), Json.parse("[]"));
    }

    @Test
    void refusesWhatIsNotStrictJsonSayingWhere() {
        assertEquals("line 2, column 1: expected a key in double quotes", message("{\"a\": 1,\n}"));
        assertEquals("line 1, column 10: the key \"a\" appears twice", message("{\"a\": 1, \"a\": 2}"));
        assertEquals("line 1, column 1: unexpected '/' where a value was expected", message("// no comments\n{}"));
        assertEquals("line 1, column 3: unexpected '{' after the value", message("{}{}"));
        assertEquals("line 1, column 2: the text ends where a value was expected", message("["));
        assertEquals("line 1, column 2: unexpected '1' after the value", message("01"));
        assertEquals("line 1, column 65: nested more than 64 levels deep", message("[".repeat(65) + "]".repeat(65)));
        assertEquals(List.of(List.of()), Json.parse("[".repeat(2) + "]".repeat(2)));
        assertEquals("line 1, column 2: unknown escape '\\x'", message("\"\\x\""));
        // a number of a million digits is refused at once, not parsed in quadratic time
        assertEquals("line 1, column 2: a number of 1000000 characters is longer than DTRON reads (at most 100)",
                message("[" + "9".repeat(1_000_000) + "]"));
        assertEquals(new BigDecimal("0." + "9".repeat(98)), Json.parse("0." + "9".repeat(98)));
    }

    private static String message(String json) {
        return assertThrows(IllegalArgumentException.class, () -> Json.parse(json)).getMessage();
    }
}
