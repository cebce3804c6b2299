package io.dtron.bus.internal;

import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;

/**
 * Not API. The body of one JGroups message: a version byte, the group name
 * (unsigned 16-bit length, UTF-8) and then the payload.
 */
final class Frames {
    static final byte VERSION = 1;

    private Frames() {
    }

    /** A decoded frame. */
    record Frame(String group, byte[] payload) {
    }

    static byte[] encode(String group, byte[] payload) {
        byte[] name = group.getBytes(StandardCharsets.UTF_8);
        if (name.length > 0xFFFF) {
            throw new IllegalArgumentException("group name longer than 65535 bytes");
        }
        return ByteBuffer.allocate(3 + name.length + payload.length)
                .put(VERSION)
                .putShort((short) name.length)
                .put(name)
                .put(payload)
                .array();
    }

    /**
     * Decodes a frame.
     *
     * @throws IllegalArgumentException if the bytes are no frame of this version
     */
    static Frame decode(byte[] bytes, int offset, int length) {
        if (length < 3 || bytes[offset] != VERSION) {
            throw new IllegalArgumentException("not a DTRON frame (" + length + " bytes)");
        }
        int nameLength = ((bytes[offset + 1] & 0xFF) << 8) | (bytes[offset + 2] & 0xFF);
        if (3 + nameLength > length) {
            throw new IllegalArgumentException("group name runs past the end of the frame");
        }
        String group = new String(bytes, offset + 3, nameLength, StandardCharsets.UTF_8);
        byte[] payload = new byte[length - 3 - nameLength];
        System.arraycopy(bytes, offset + 3 + nameLength, payload, 0, payload.length);
        return new Frame(group, payload);
    }
}
