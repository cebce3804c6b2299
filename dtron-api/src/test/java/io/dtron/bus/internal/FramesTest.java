package io.dtron.bus.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import org.junit.jupiter.api.Test;

class FramesTest {

    @Test
    void roundTripAtAnOffset() {
        byte[] frame = Frames.encode("move", new byte[] {1, 2, 3});
        byte[] padded = new byte[frame.length + 4];
        System.arraycopy(frame, 0, padded, 2, frame.length);
        Frames.Frame decoded = Frames.decode(padded, 2, frame.length);
        assertEquals("move", decoded.group());
        assertArrayEquals(new byte[] {1, 2, 3}, decoded.payload());
    }

    @Test
    void emptyPayload() {
        byte[] frame = Frames.encode("done", new byte[0]);
        assertEquals(0, Frames.decode(frame, 0, frame.length).payload().length);
    }

    @Test
    void rejectsForeignAndTruncatedFrames() {
        assertThrows(IllegalArgumentException.class, () -> Frames.decode(new byte[] {9, 0, 0}, 0, 3));
        assertThrows(IllegalArgumentException.class, () -> Frames.decode(new byte[] {1, 0}, 0, 2));
        byte[] frame = Frames.encode("move", new byte[0]);
        assertThrows(IllegalArgumentException.class, () -> Frames.decode(frame, 0, frame.length - 1));
    }
}
