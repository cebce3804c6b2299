package io.dtron.cli;

import java.io.ByteArrayOutputStream;
import java.io.OutputStream;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;

/** Copies the output of a child process to a writer, line by line, each line behind a prefix. */
final class LineEcho extends OutputStream {
    private final PrintWriter to;
    private final String prefix;
    private final ByteArrayOutputStream line = new ByteArrayOutputStream();

    LineEcho(PrintWriter to, String prefix) {
        this.to = to;
        this.prefix = prefix;
    }

    @Override
    public synchronized void write(int b) {
        if (b == '\n') {
            flushLine();
        } else if (b != '\r') {
            line.write(b);
        }
    }

    @Override
    public synchronized void flush() {
        to.flush();
    }

    @Override
    public synchronized void close() {
        if (line.size() > 0) {
            flushLine();
        }
        to.flush();
    }

    private void flushLine() {
        to.println(prefix + line.toString(StandardCharsets.UTF_8));
        to.flush();
        line.reset();
    }
}
