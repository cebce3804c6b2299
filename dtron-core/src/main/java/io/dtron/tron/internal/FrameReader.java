package io.dtron.tron.internal;

import io.dtron.tron.TronProtocolException;
import java.io.EOFException;
import java.io.IOException;
import java.io.InputStream;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;

/**
 * Reads TRON's frames from a socket with strict bounds. Waiting for the first byte of a frame may take as long as
 * the caller allows; once a frame has begun, the rest must arrive within the frame timeout, or the frame is
 * reported as truncated, so that a peer that stops in the middle of a frame never hangs the run. A connection
 * closed between frames is {@link EOFException}; closed inside a frame, a {@link TronProtocolException}.
 */
public final class FrameReader {
    private final InputStream in;
    private final long frameTimeoutNanos;
    private final byte[] buffer = new byte[4];
    private volatile long frameStart;
    private volatile boolean inFrame;

    /** A reader of {@code socket}; sets the socket's read timeout to poll for the frame timeout. */
    public FrameReader(Socket socket, Duration frameTimeout) throws IOException {
        this.in = socket.getInputStream();
        this.frameTimeoutNanos = frameTimeout.toNanos();
        socket.setSoTimeout((int) Math.max(20, Math.min(1000, frameTimeout.toMillis() / 4)));
    }

    /**
     * Waits for the first byte of a frame until {@code deadlineNanos} (of {@link System#nanoTime()}; {@link
     * Long#MAX_VALUE} for no limit) and returns it, unsigned.
     *
     * @throws EOFException              when the connection was closed between frames
     * @throws SocketTimeoutException    when the deadline passed first
     */
    public int firstByte(long deadlineNanos) throws IOException {
        while (true) {
            int b;
            try {
                b = in.read();
            } catch (SocketTimeoutException e) {
                if (System.nanoTime() - deadlineNanos >= 0) {
                    throw e;
                }
                continue;
            }
            if (b < 0) {
                throw new EOFException("the connection was closed");
            }
            frameStart = System.nanoTime();
            inFrame = true;
            return b;
        }
    }

    /** Marks the end of the current frame: its last field was read. */
    public void endFrame() {
        inFrame = false;
    }

    /** Whether a frame has begun and its end was not marked yet. */
    public boolean inFrame() {
        return inFrame;
    }

    /** When the current (or last) frame's first byte came, in {@link System#nanoTime()}. */
    public long frameStartNanos() {
        return frameStart;
    }

    /** The frame timeout. */
    public Duration frameTimeout() {
        return Duration.ofNanos(frameTimeoutNanos);
    }

    /** Waits without limit for the first int32 of a frame (an event's channel id, or an acknowledgement). */
    public int firstInt() throws IOException {
        return int32Reply(Long.MAX_VALUE, "the channel id of an event");
    }

    /** An int32 inside the current frame; {@code what} names it in messages. */
    public int int32(String what) throws IOException {
        readFully(4, what);
        return ((buffer[0] & 0xff) << 24) | ((buffer[1] & 0xff) << 16) | ((buffer[2] & 0xff) << 8)
                | (buffer[3] & 0xff);
    }

    /** An unsigned 16-bit number inside the current frame. */
    public int uint16(String what) throws IOException {
        readFully(2, what);
        return ((buffer[0] & 0xff) << 8) | (buffer[1] & 0xff);
    }

    /** A string (length byte and bytes) inside the current frame, decoded as UTF-8. */
    public String string(String what) throws IOException {
        readFully(1, "the length of " + what);
        int length = buffer[0] & 0xff;
        byte[] bytes = new byte[length];
        readInto(bytes, 0, length, what + " (" + length + " bytes announced)");
        return new String(bytes, StandardCharsets.UTF_8);
    }

    /** A string that is a whole reply (the tester's answer to start or explain), waiting up to the deadline. */
    public String stringReply(long deadlineNanos, String what) throws IOException {
        int length = firstByte(deadlineNanos);
        byte[] bytes = new byte[length];
        readInto(bytes, 0, length, what + " (" + length + " bytes announced)");
        return new String(bytes, StandardCharsets.UTF_8);
    }

    /** An int32 that is a whole reply, waiting up to the deadline for its first byte. */
    public int int32Reply(long deadlineNanos, String what) throws IOException {
        int first = firstByte(deadlineNanos);
        readInto(buffer, 1, 3, what);
        return (first << 24) | ((buffer[0] & 0xff) << 16) | ((buffer[1] & 0xff) << 8) | (buffer[2] & 0xff);
    }

    private void readFully(int length, String what) throws IOException {
        readInto(buffer, 0, length, what);
    }

    /**
     * Reads {@code length} bytes of a field of which {@code before} bytes were read already (they count in
     * messages).
     */
    private void readInto(byte[] target, int before, int length, String what) throws IOException {
        int got = 0;
        while (got < length) {
            int n;
            try {
                n = in.read(target, got, length - got);
            } catch (SocketTimeoutException e) {
                if (System.nanoTime() - frameStart >= frameTimeoutNanos) {
                    throw new TronProtocolException("truncated frame: " + what + " did not arrive within "
                            + Duration.ofNanos(frameTimeoutNanos).toMillis() + " ms (" + (before + got) + " of "
                            + (before + length) + " bytes came)");
                }
                continue;
            }
            if (n < 0) {
                throw new TronProtocolException("the connection was closed in the middle of a frame, while reading "
                        + what + " (" + (before + got) + " of " + (before + length) + " bytes came)");
            }
            got += n;
        }
    }
}
