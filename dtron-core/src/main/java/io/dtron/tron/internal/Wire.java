package io.dtron.tron.internal;

import io.dtron.engine.Event;
import io.dtron.model.TestInterface;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.util.List;

/**
 * The constants and frame layouts of TRON's socket-adapter protocol: all integers big-endian, a string is one
 * unsigned length byte and that many bytes.
 */
public final class Wire {
    /** Registers an input channel: {@code [1][string]}, answered with an int32 id or error code. */
    public static final int INPUT = 1;
    /** Registers an output channel: {@code [2][string]}. */
    public static final int OUTPUT = 2;
    /** Attaches a variable to an input: {@code [3][int32 id][string]}, answered with an int32. */
    public static final int INPUT_VARIABLE = 3;
    /** Attaches a variable to an output: {@code [4][int32 id][string]}. */
    public static final int OUTPUT_VARIABLE = 4;
    /** Sets the model time unit: {@code [5][int32 seconds][int32 microseconds]}. */
    public static final int TIME_UNIT = 5;
    /** Sets the timeout in model time units: {@code [6][int32]}. */
    public static final int TIMEOUT = 6;
    /** Starts testing: {@code [64]}, answered with a string, empty when accepted. */
    public static final int START = 64;
    /** Asks for the explanation of an error code: {@code [127][int32 code]}, answered with a string. */
    public static final int EXPLAIN = 127;
    /**
     * DTRON's extension, never sent by TRON's own adapters: {@code [200]} asks for the shared virtual clock
     * (time grants and the adapter's next timer as events on channel 0). Answered with an int32.
     */
    public static final int VIRTUAL_CLOCK = 200;

    /** Bit 31 marks an acknowledgement in virtual time; channel ids never have it. */
    public static final int ACK_BIT = 0x8000_0000;
    /** The channel id of the shared virtual clock's messages (DTRON's extension); real channel ids are positive. */
    public static final int CLOCK_CHANNEL = 0;
    /** "No timer pending", in the adapter's clock message. */
    public static final long NO_TIMER = -1;
    /** The longest string the protocol can carry. */
    public static final int MAX_STRING = 255;

    private Wire() {
    }

    /** A command with a string argument. */
    public static byte[] command(int command, String text) {
        byte[] s = stringBytes(text);
        return ByteBuffer.allocate(2 + s.length).put((byte) command).put((byte) s.length).put(s).array();
    }

    /** A command with an int32 and a string argument. */
    public static byte[] command(int command, int value, String text) {
        byte[] s = stringBytes(text);
        return ByteBuffer.allocate(6 + s.length).put((byte) command).putInt(value).put((byte) s.length).put(s)
                .array();
    }

    /** A command with int32 arguments. */
    public static byte[] command(int command, int... values) {
        ByteBuffer b = ByteBuffer.allocate(1 + 4 * values.length).put((byte) command);
        for (int v : values) {
            b.putInt(v);
        }
        return b.array();
    }

    /** An int32 reply. */
    public static byte[] int32(int value) {
        return ByteBuffer.allocate(4).putInt(value).array();
    }

    /** A string reply. */
    public static byte[] string(String text) {
        byte[] s = stringBytes(text);
        return ByteBuffer.allocate(1 + s.length).put((byte) s.length).put(s).array();
    }

    /** The values of an event's attached variables in their wire order, the order they were registered in. */
    public static int[] values(List<TestInterface.AttachedVariable> variables, Event event) {
        int[] values = new int[variables.size()];
        for (int i = 0; i < values.length; i++) {
            values[i] = event.value(variables.get(i).name());
        }
        return values;
    }

    /** An event: {@code [int32 channel][uint16 n][n x int32]}. */
    public static byte[] event(int channel, int[] values) {
        if (values.length > 0xffff) {
            throw new IllegalArgumentException("an event carries at most 65535 values");
        }
        ByteBuffer b = ByteBuffer.allocate(6 + 4 * values.length).putInt(channel).putShort((short) values.length);
        for (int v : values) {
            b.putInt(v);
        }
        return b.array();
    }

    /** An acknowledgement of {@code n} events. */
    public static byte[] ack(int n) {
        return int32(ACK_BIT | n);
    }

    /** A message of the shared virtual clock: a time in microseconds as two int32 (high, low) on channel 0. */
    public static byte[] clock(long micros) {
        return event(CLOCK_CHANNEL, new int[] {(int) (micros >>> 32), (int) micros});
    }

    /** The time of a clock message's two values. */
    public static long clockMicros(int high, int low) {
        return ((long) high << 32) | (low & 0xffff_ffffL);
    }

    /**
     * The bytes of a string on the wire (UTF-8): at most {@value #MAX_STRING}; longer texts are cut, ending in
     * "...".
     */
    public static byte[] stringBytes(String text) {
        byte[] bytes = text.getBytes(StandardCharsets.UTF_8);
        if (bytes.length <= MAX_STRING) {
            return bytes;
        }
        String cut = text;
        while (bytes.length > MAX_STRING) {
            cut = cut.substring(0, cut.length() - Math.max(1, (bytes.length - MAX_STRING) / 2));
            bytes = (cut + "...").getBytes(StandardCharsets.UTF_8);
        }
        return bytes;
    }

    /** A string from the wire, with control characters shown as {@code \xNN}, for messages. */
    public static String printable(String text) {
        StringBuilder sb = new StringBuilder();
        for (char c : text.toCharArray()) {
            if (c < 32 || c == 127) {
                sb.append(String.format("\\x%02x", (int) c));
            } else {
                sb.append(c);
            }
        }
        return sb.toString();
    }
}
