package io.dtron.report.internal;

import io.dtron.engine.JsonString;
import java.util.List;
import java.util.Map;

/**
 * JSON text for the report's data block: string literals safe inside an HTML {@code <script>} element ({@code <},
 * {@code >}, {@code &} and the line separators escaped), lists and maps of plain values.
 */
public final class JsonText {
    private JsonText() {
    }

    /** {@code s} as a JSON string literal, or {@code null}. */
    public static String quote(String s) {
        if (s == null) {
            return "null";
        }
        StringBuilder sb = new StringBuilder(s.length() + 2);
        quote(s, sb);
        return sb.toString();
    }

    /** Appends {@code s} as a JSON string literal safe inside an HTML script element (see {@link JsonString}). */
    public static void quote(String s, StringBuilder sb) {
        JsonString.quote(s, sb, true);
    }

    /** Appends a list of strings. */
    public static void strings(List<String> list, StringBuilder sb) {
        sb.append('[');
        for (int i = 0; i < list.size(); i++) {
            if (i > 0) {
                sb.append(',');
            }
            quote(list.get(i), sb);
        }
        sb.append(']');
    }

    /** Appends {@code a=1, b=2} of a channel's values as one string literal. */
    public static void values(Map<String, Integer> values, StringBuilder sb) {
        StringBuilder text = new StringBuilder();
        for (Map.Entry<String, Integer> v : values.entrySet()) {
            text.append(text.length() == 0 ? "" : ", ").append(v.getKey()).append('=').append(v.getValue());
        }
        quote(text.toString(), sb);
    }

    /** Appends a list of ints. */
    public static void ints(int[] values, int count, StringBuilder sb) {
        sb.append('[');
        for (int i = 0; i < count; i++) {
            sb.append(i == 0 ? "" : ",").append(values[i]);
        }
        sb.append(']');
    }
}
