package io.dtron.api.internal;

import com.google.protobuf.InvalidProtocolBufferException;
import io.dtron.api.InvalidMessageException;
import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.api.internal.proto.Sync;
import io.dtron.api.internal.proto.Variable;
import java.util.Collection;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

/** Not API. Encodes and decodes {@code Sync} messages and checks them against a channel template. */
public final class SyncCodec {
    private SyncCodec() {
    }

    /** Encodes a message with sender, sequence and publish time only (the event time is the publish time). */
    public static byte[] encode(String channelName, Map<String, Integer> variables, String sender, long sequence,
            long publishTimeNanos) {
        return encode(channelName, variables, new Stamp(sender, sequence, publishTimeNanos, 0, "", "", 0, 0, 0));
    }

    /**
     * Encodes a message; fields 1 and 2 are always written, the others when not 0 or empty. The event time is left
     * out when it equals the publish time.
     */
    public static byte[] encode(String channelName, Map<String, Integer> variables, Stamp stamp) {
        return builder(channelName, variables, stamp).build().toByteArray();
    }

    /**
     * Encodes a message with a text (field 18, on DTRON's channels that carry one; "" writes none), the announced
     * end of a run (field 19, on a tester's run start; 0 writes none) and the due time of an input sent ahead (field
     * 22; 0 writes none).
     */
    public static byte[] encode(String channelName, Map<String, Integer> variables, Stamp stamp, String text,
            long endTimeNanos, long dueTimeNanos) {
        return builder(channelName, variables, stamp).setText(text).setEndTimeNs(endTimeNanos)
                .setDueTimeNs(dueTimeNanos).build().toByteArray();
    }

    private static Sync.Builder builder(String channelName, Map<String, Integer> variables, Stamp stamp) {
        Sync.Builder sync = Sync.newBuilder()
                .setName(channelName)
                .setSender(stamp.sender())
                .setSequence(stamp.sequence())
                .setPublishTimeNs(stamp.publishTimeNanos())
                .setRunId(stamp.runId())
                .setAckedSender(stamp.ackedSender())
                .setAckedSequence(stamp.ackedSequence())
                .setClockOffsetNs(stamp.clockOffsetNanos())
                .setClockErrorNs(stamp.clockErrorNanos());
        if (stamp.eventTimeNanos() != stamp.publishTimeNanos()) {
            sync.setEventTimeNs(stamp.eventTimeNanos());
        }
        variables.forEach((name, value) -> sync.addVariables(Variable.newBuilder().setName(name).setValue(value)));
        return sync;
    }

    /**
     * Encodes a message of the clock-offset protocol, without variables; {@code asInput} (on a ping) asks the members
     * to answer it as they acknowledge an input, {@code probe} (on a ping) asks every member to answer it, whoever
     * sent it; {@code hostClock} is the sender's {@link HostClock} id, or ""; {@code endTimeNanos} (on a tester's
     * pong during a run) the end of the run its start announced, else 0.
     */
    public static byte[] encodeControl(String channelName, Stamp stamp, boolean asInput, boolean probe,
            String hostClock, long endTimeNanos) {
        return builder(channelName, Map.of(), stamp).setAsInput(asInput).setProbe(probe).setHostClock(hostClock)
                .setEndTimeNs(endTimeNanos).build().toByteArray();
    }

    /**
     * Encodes a {@code dtron_serve} message of the channel-serving handshake: no variables, the channels the sender
     * receives and sends, and that it holds inputs sent ahead until they are due (field 21), as every member of this
     * API does.
     */
    public static byte[] encodeServed(String channelName, Stamp stamp, Collection<String> receives,
            Collection<String> sends, boolean joinsRun, boolean tester) {
        return builder(channelName, Map.of(), stamp).addAllReceives(receives).addAllSends(sends).setJoinsRun(joinsRun)
                .setTester(tester).setHoldsInputs(true).build().toByteArray();
    }

    /** Returns the stamp a parsed message carries, with {@code transportSender} when it names no sender. */
    public static Stamp stamp(Sync sync, String transportSender) {
        String sender = sync.getSender().isEmpty() ? transportSender : sync.getSender();
        return new Stamp(sender, sync.getSequence(), sync.getPublishTimeNs(), sync.getEventTimeNs(), sync.getRunId(),
                sync.getAckedSender(), sync.getAckedSequence(), sync.getClockOffsetNs(), sync.getClockErrorNs());
    }

    /**
     * Encodes, parses and decodes one message and makes a value to send, so that the protocol-buffer classes and the
     * code of a channel's values are loaded and first run (tens of milliseconds in a fresh JVM) before the first
     * real message, not when a run's first messages have milliseconds to arrive.
     */
    public static void warmUp() {
        DtronChannel channel = new DtronChannel("warm_up", List.of("v"));
        decode(channel, parse(encode(channel.getChannelName(), Map.of("v", 1), "", 1, 1)), "", 1);
        DtronChannelValued.published(channel, channel.constructValued(Map.of("v", 1)).getVariables(), Stamp.NONE);
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
        return new DtronChannelValued(template, ordered, stamp(sync, transportSender), receiveTimeNanos,
                sync.getText(), sync.getEndTimeNs(), sync.getDueTimeNs());
    }
}
