package io.dtron.api.internal;

import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Objects;

/** Not API. The immutable {@link IDtronChannelValued}. */
public final class DtronChannelValued implements IDtronChannelValued {
    private final DtronChannel channel;
    private final Map<String, Integer> variables;
    private final String sender;
    private final long sequence;
    private final long publishTimeNanos;
    private final long receiveTimeNanos;

    DtronChannelValued(DtronChannel channel, Map<String, Integer> variables, String sender, long sequence,
            long publishTimeNanos, long receiveTimeNanos) {
        this.channel = channel;
        this.variables = Collections.unmodifiableMap(new LinkedHashMap<>(variables));
        this.sender = Objects.requireNonNull(sender, "sender");
        this.sequence = sequence;
        this.publishTimeNanos = publishTimeNanos;
        this.receiveTimeNanos = receiveTimeNanos;
    }

    @Override
    public String getChannelName() {
        return channel.getChannelName();
    }

    @Override
    public IDtronChannel getChannel() {
        return channel;
    }

    @Override
    public Map<String, Integer> getVariables() {
        return variables;
    }

    @Override
    public String getSender() {
        return sender;
    }

    @Override
    public long getSequence() {
        return sequence;
    }

    @Override
    public long getPublishTimeNanos() {
        return publishTimeNanos;
    }

    @Override
    public long getReceiveTimeNanos() {
        return receiveTimeNanos;
    }

    @Override
    public byte[] toByteArray() {
        return SyncCodec.encode(getChannelName(), variables, sender, sequence, publishTimeNanos);
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof DtronChannelValued other
                && channel.equals(other.channel)
                && variables.equals(other.variables)
                && sender.equals(other.sender)
                && sequence == other.sequence
                && publishTimeNanos == other.publishTimeNanos
                && receiveTimeNanos == other.receiveTimeNanos;
    }

    @Override
    public int hashCode() {
        return Objects.hash(channel, variables, sender, sequence, publishTimeNanos, receiveTimeNanos);
    }

    @Override
    public String toString() {
        StringBuilder text = new StringBuilder(channel.getChannelName()).append(variables);
        if (!sender.isEmpty()) {
            text.append(" from ").append(sender).append('#').append(sequence);
        }
        return text.toString();
    }
}
