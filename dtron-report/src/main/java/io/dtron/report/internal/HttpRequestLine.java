package io.dtron.report.internal;

import java.io.IOException;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;

/** Reads the head of an HTTP request (at most {@link #MAX} bytes) and returns the path of a GET, else null. */
public final class HttpRequestLine {
    /** The longest request head read. */
    public static final int MAX = 8192;

    private HttpRequestLine() {
    }

    /** The path of the GET request on {@code in} without its query, or null when it is none. */
    public static String read(InputStream in) throws IOException {
        byte[] head = new byte[MAX];
        int n = 0;
        while (n < MAX) {
            int b = in.read();
            if (b < 0) {
                return null;
            }
            head[n++] = (byte) b;
            if (n >= 4 && head[n - 4] == '\r' && head[n - 3] == '\n' && head[n - 2] == '\r' && head[n - 1] == '\n') {
                break;
            }
        }
        String text = new String(head, 0, n, StandardCharsets.US_ASCII);
        int eol = text.indexOf("\r\n");
        String[] line = (eol < 0 ? text : text.substring(0, eol)).split(" ");
        if (line.length != 3 || !line[0].equals("GET") || !line[1].startsWith("/") || !line[2].startsWith("HTTP/")) {
            return null;
        }
        int query = line[1].indexOf('?');
        return query < 0 ? line[1] : line[1].substring(0, query);
    }
}
