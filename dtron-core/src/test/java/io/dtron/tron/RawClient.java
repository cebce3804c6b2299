package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.io.BufferedOutputStream;
import java.io.Closeable;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.net.Socket;
import java.net.SocketException;
import java.nio.charset.StandardCharsets;

/** A hand-written adapter that sends exactly the bytes a test asks for, well-formed or not. */
final class RawClient implements Closeable {
    private final Socket socket;
    private final DataOutputStream out;
    private final DataInputStream in;

    RawClient(int port) throws IOException {
        this(new Socket("127.0.0.1", port));
    }

    private RawClient(Socket socket) throws IOException {
        this.socket = socket;
        socket.setTcpNoDelay(true);
        socket.setSoTimeout(10_000);
        // each call's bytes leave in one write, as a real adapter's would: a busy machine may hold up the test
        // between calls, not in the middle of a number
        out = new DataOutputStream(new BufferedOutputStream(socket.getOutputStream()));
        in = new DataInputStream(socket.getInputStream());
    }

    /** A raw client on a socket the tester connected to. */
    static RawClient over(Socket socket) throws IOException {
        return new RawClient(socket);
    }

    RawClient bytes(int... values) throws IOException {
        for (int v : values) {
            out.write(v);
        }
        out.flush();
        return this;
    }

    RawClient int32(int value) throws IOException {
        out.writeInt(value);
        out.flush();
        return this;
    }

    RawClient uint16(int value) throws IOException {
        out.writeShort(value);
        out.flush();
        return this;
    }

    /** A string with the length byte {@code announced}, which may differ from its true length. */
    RawClient string(int announced, String text) throws IOException {
        out.write(announced);
        out.write(text.getBytes(StandardCharsets.US_ASCII));
        out.flush();
        return this;
    }

    RawClient string(String text) throws IOException {
        return string(text.length(), text);
    }

    int readInt() throws IOException {
        return in.readInt();
    }

    int readUint16() throws IOException {
        return in.readUnsignedShort();
    }

    String readString() throws IOException {
        int length = in.readUnsignedByte();
        byte[] bytes = new byte[length];
        in.readFully(bytes);
        return new String(bytes, StandardCharsets.UTF_8);
    }

    /** Whether the tester has closed the connection (what is left to read ends, or the connection is reset). */
    boolean closedByTester() throws IOException {
        try {
            while (true) {
                if (in.read() < 0) {
                    return true;
                }
            }
        } catch (SocketException e) {
            return true;
        }
    }

    /** Registers LightContr's interface, 1000 us per unit, the timeout, and starts. */
    RawClient configureLamp(int timeout) throws IOException {
        bytes(1).string("grasp");
        assertEquals(1, readInt());
        bytes(1).string("release");
        assertEquals(2, readInt());
        bytes(2).string("level");
        assertEquals(3, readInt());
        bytes(4).int32(3).string("adapLevel");
        assertEquals(0, readInt());
        bytes(5).int32(0).int32(1000);
        assertEquals(0, readInt());
        bytes(6).int32(timeout);
        assertEquals(0, readInt());
        bytes(64);
        assertEquals("", readString());
        return this;
    }

    @Override
    public void close() throws IOException {
        socket.close();
    }
}
