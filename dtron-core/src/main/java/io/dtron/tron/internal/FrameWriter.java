package io.dtron.tron.internal;

import java.io.IOException;
import java.io.OutputStream;
import java.net.Socket;

/**
 * Writes whole frames to a socket, one at a time: outputs, inputs, acknowledgements and clock messages from
 * different threads never interleave. TCP_NODELAY is set, so that every frame leaves at once.
 */
public final class FrameWriter {
    private final OutputStream out;

    /** A writer to {@code socket}. */
    public FrameWriter(Socket socket) throws IOException {
        socket.setTcpNoDelay(true);
        this.out = socket.getOutputStream();
    }

    /** Writes one frame (or several, concatenated) and flushes it. */
    public synchronized void write(byte[] frame) throws IOException {
        out.write(frame);
        out.flush();
    }
}
