package io.dtron.api.internal;

import com.google.protobuf.InvalidProtocolBufferException;
import io.dtron.api.InvalidMessageException;
import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.api.internal.proto.Sync;
import io.dtron.api.internal.proto.Variable;
import java.util.LinkedHashMap;
import java.util.Map;

/** Not API. Encodes and decodes {@code Sync} messages and checks them against a channel template. */
public final class SyncCodec {
    private SyncCodec() {
    }

    /** Encodes a message; old fields are always written, new fields when not 0 or empty. */
    public static byte[] encode(String channelName, Map<String, Integer> variables, String sender, long sequence,
            long publishTimeNanos) {
        Sync.Builder sync = Sync.newBuilder()
                .setName(channelName)
                .setSender(sender)
                .setSequence(sequence)
                .setPublishTimeNs(publishTimeNanos);
        variables.forEach((name, value) -> sync.addVariables(Variable.newBuilder().setName(name).setValue(value)));
        return sync.build().toByteArray();
    }

    /**
     * Encodes and parses one message, so that the protocol-buffer classes are loaded and initialised (tens of
     * milliseconds in a fresh JVM) before the first real message.
     */
    public static void warmUp() {
        parse(encode("warm_up", Map.of("v", 1), "", 1, 1));
    }

    /**
     * Parses the bytes of a {@code Sync}.
     *
     * @throws InvalidMessageException ({@link Reason#MALFORMED}) if they are none, or it has no channel name
     */
    public static Sync parse(byte[] bytes) {
        Sync sync;
        try {
            sync = Sync.parseFrom(bytes);
        } catch (InvalidProtocolBufferException e) {
            throw new InvalidMessageException(Reason.MALFORMED, "not a Sync message (" + bytes.length + " bytes): "
                    + e.getMessage());
        }
        if (!sync.hasName() || sync.getName().isEmpty()) {
            throw new InvalidMessageException(Reason.MALFORMED, "Sync message without a channel name");
        }
        return sync;
    }

    /**
     * Checks a parsed message against a template and makes it a value.
     *
     * @param transportSender  the sender the bus reported, used when the message names none
     * @param receiveTimeNanos when it arrived, 0 if it did not come from the bus
     * @throws InvalidMessageException if it names another channel, has a nameless or repeated
     *                                 variable, or unknown or missing variables
     */
    public static DtronChannelValued decode(DtronChannel template, Sync sync, String transportSender,
            long receiveTimeNanos) {
        if (!sync.getName().equals(template.getChannelName())) {
            throw new InvalidMessageException(Reason.UNKNOWN_CHANNEL, "message names channel '" + sync.getName()
                    + "', expected '" + template.getChannelName() + "'");
        }
        Map<String, Integer> values = new LinkedHashMap<>();
        for (Variable variable : sync.getVariablesList()) {
            if (!variable.hasName() || variable.getName().isEmpty()) {
                throw new InvalidMessageException(Reason.MALFORMED, "variable without a name in channel "
                        + sync.getName());
            }
            // an absent value is 0: plain proto3 senders leave zeros out
            if (values.put(variable.getName(), variable.getValue()) != null) {
                throw new InvalidMessageException(Reason.MALFORMED, "variable " + variable.getName()
                        + " appears twice in channel " + sync.getName());
            }
        }
        template.checkVariables(values.keySet());
        Map<String, Integer> ordered = new LinkedHashMap<>();
        template.getVariableNames().forEach(name -> ordered.put(name, values.get(name)));
        String sender = sync.getSender().isEmpty() ? transportSender : sync.getSender();
        return new DtronChannelValued(template, ordered, sender, sync.getSequence(), sync.getPublishTimeNs(),
                receiveTimeNanos);
    }
}
