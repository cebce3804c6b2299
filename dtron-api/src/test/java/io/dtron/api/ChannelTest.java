package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import com.google.protobuf.CodedOutputStream;
import com.google.protobuf.UnknownFieldSet;
import io.dtron.api.InvalidMessageException.Reason;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;

class ChannelTest {
    private final IDtronChannel move = IDtronChannel.of("move", "amount", "speed");

    @Test
    void templateKeepsNameAndVariablesInOrder() {
        assertEquals("move", move.getChannelName());
        assertEquals(List.of("amount", "speed"), move.getVariableNames());
        assertEquals(move, IDtronChannel.of("move", List.of("amount", "speed")));
        assertThrows(UnsupportedOperationException.class, () -> move.getVariableNames().add("x"));
    }

    @Test
    void templateRejectsBadNames() {
        assertThrows(IllegalArgumentException.class, () -> IDtronChannel.of("i move"));
        assertThrows(IllegalArgumentException.class, () -> IDtronChannel.of("move", "a", "a"));
        assertThrows(IllegalArgumentException.class, () -> IDtronChannel.of("move", "1a"));
    }

    @Test
    void fromModelDropsPrefixes() {
        assertEquals(IDtronChannel.of("move", "amount"), IDtronChannel.fromModel("i_move", List.of("i_move_amount")));
        assertEquals(IDtronChannel.of("done"), IDtronChannel.fromModel("o_done", List.of()));
        assertEquals(IDtronChannel.of("level", "adapLevel"), IDtronChannel.fromModel("level", List.of("adapLevel")));
    }

    @Test
    void valuesAreImmutableAndInTemplateOrder() {
        Map<String, Integer> input = new HashMap<>(Map.of("speed", 2, "amount", 7));
        IDtronChannelValued value = move.constructValued(input);
        input.put("amount", 8);
        assertEquals(List.of("amount", "speed"), List.copyOf(value.getVariables().keySet()));
        assertEquals(7, value.getVariables().get("amount"));
        assertThrows(UnsupportedOperationException.class, () -> value.getVariables().put("amount", 1));
        assertEquals("", value.getSender());
        assertEquals(0, value.getReceiveTimeNanos());
    }

    @Test
    void unknownVariableIsAnError() {
        InvalidMessageException e = assertThrows(InvalidMessageException.class,
                () -> move.constructValued(Map.of("amount", 1, "speed", 2, "colour", 3)));
        assertEquals(Reason.UNKNOWN_VARIABLES, e.getReason());
        assertTrue(e.getMessage().contains("colour"), e.getMessage());
    }

    @Test
    void missingVariableIsAnError() {
        InvalidMessageException e = assertThrows(InvalidMessageException.class,
                () -> move.constructValued(Map.of("amount", 1)));
        assertEquals(Reason.MISSING_VARIABLES, e.getReason());
        assertTrue(e.getMessage().contains("speed"), e.getMessage());
    }

    @Test
    void bytesRoundTrip() {
        IDtronChannelValued value = move.constructValued(Map.of("amount", -5, "speed", 0));
        IDtronChannelValued decoded = move.constructValued(value.toByteArray());
        assertEquals(value.getVariables(), decoded.getVariables());
        assertEquals(value, decoded);
    }

    @Test
    void garbageIsMalformed() {
        InvalidMessageException e = assertThrows(InvalidMessageException.class,
                () -> move.constructValued(new byte[] {(byte) 0xFF, 0x01, 0x02}));
        assertEquals(Reason.MALFORMED, e.getReason());
    }

    @Test
    void messageOfAnotherChannelIsUnknownChannel() {
        byte[] done = IDtronChannel.of("done").constructValued(Map.of()).toByteArray();
        assertEquals(Reason.UNKNOWN_CHANNEL,
                assertThrows(InvalidMessageException.class, () -> move.constructValued(done)).getReason());
    }

    /** What an adapter built against the original Sync.proto writes: fields 1 and 2 only, zero left out. */
    @Test
    void decodesOldAdapterMessages() throws IOException {
        byte[] amount = message(out -> {
            out.writeString(1, "amount");
            out.writeSInt32(2, -3);
        });
        byte[] speed = message(out -> out.writeString(1, "speed"));
        byte[] sync = message(out -> {
            out.writeString(1, "move");
            out.writeByteArray(2, amount);
            out.writeByteArray(2, speed);
        });
        IDtronChannelValued value = move.constructValued(sync);
        assertEquals(Map.of("amount", -3, "speed", 0), value.getVariables());
        assertEquals(0, value.getSequence());
    }

    /** Old decoders rely on field numbers and wire types 1 and 2, and on zero values being written. */
    @Test
    void writesOldFieldNumbersAndTypes() throws IOException {
        byte[] bytes = move.constructValued(Map.of("amount", -3, "speed", 0)).toByteArray();
        UnknownFieldSet sync = UnknownFieldSet.parseFrom(bytes);
        assertEquals(List.of("move"), sync.getField(1).getLengthDelimitedList().stream()
                .map(b -> b.toStringUtf8()).toList());
        assertEquals(2, sync.getField(2).getLengthDelimitedList().size());
        UnknownFieldSet speed = UnknownFieldSet.parseFrom(sync.getField(2).getLengthDelimitedList().get(1));
        assertEquals("speed", speed.getField(1).getLengthDelimitedList().get(0).toStringUtf8());
        assertEquals(List.of(0L), speed.getField(2).getVarintList(), "a zero value is written");
        UnknownFieldSet amountVar = UnknownFieldSet.parseFrom(sync.getField(2).getLengthDelimitedList().get(0));
        assertEquals(List.of(5L), amountVar.getField(2).getVarintList(), "sint32 zig-zag encoding of -3");
    }

    @Test
    void zeroVariableChannel() {
        IDtronChannel done = IDtronChannel.of("done");
        IDtronChannelValued value = done.constructValued(Map.of());
        assertArrayEquals(value.toByteArray(), done.constructValued(value.toByteArray()).toByteArray());
        assertTrue(value.getVariables().isEmpty());
    }

    private interface Writer {
        void write(CodedOutputStream out) throws IOException;
    }

    private static byte[] message(Writer writer) throws IOException {
        ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        CodedOutputStream out = CodedOutputStream.newInstance(bytes);
        writer.write(out);
        out.flush();
        return bytes.toByteArray();
    }
}
