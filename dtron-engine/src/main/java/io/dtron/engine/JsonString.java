package io.dtron.engine;

/**
 * JSON string literals as DTRON writes them in its traces, reports and alarms: {@code "} and {@code \} escaped,
 * {@code \n}, {@code \r} and {@code \t} by name and the other control characters as {@code \}{@code u00XX}; inside an
 * HTML {@code <script>} element also {@code <}, {@code >}, {@code &} and the line separators U+2028 and U+2029.
 */
public final class JsonString {
    private JsonString() {
    }

    /** {@code s} as a JSON string literal. */
    public static String quote(String s) {
        StringBuilder sb = new StringBuilder(s.length() + 2);
        quote(s, sb, false);
        return sb.toString();
    }

    /** Appends {@code s} as a JSON string literal; {@code inHtml}: one safe inside an HTML script element too. */
    public static void quote(String s, StringBuilder sb, boolean inHtml) {
        sb.append('"');
        for (int i = 0; i < s.length(); i++) {
            char c = s.charAt(i);
            switch (c) {
                case '"' -> sb.append("\\\"");
                case '\\' -> sb.append("\\\\");
                case '\n' -> sb.append("\\n");
                case '\r' -> sb.append("\\r");
                case '\t' -> sb.append("\\t");
                case '<', '>', '&', '\u2028', '\u2029' -> {
                    if (inHtml) {
                        sb.append(String.format("\\u%04x", (int) c));
                    } else {
                        sb.append(c);
                    }
                }
                default -> {
                    if (c < 0x20) {
                        sb.append(String.format("\\u%04x", (int) c));
                    } else {
                        sb.append(c);
                    }
                }
            }
        }
        sb.append('"');
    }
}
