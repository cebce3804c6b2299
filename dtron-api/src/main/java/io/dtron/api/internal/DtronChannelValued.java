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
    private final Stamp stamp;
    private final long receiveTimeNanos;
    private final String text;
    /** On a tester's run start, the announced end of the run (see {@link #getEndTimeNanos()}); else 0. */
    private final long endTimeNanos;
    /** On an input the tester sent ahead, when it is due (see {@link #getDueTimeNanos()}); else 0. */
    private final long dueTimeNanos;

    DtronChannelValued(DtronChannel channel, Map<String, Integer> variables, Stamp stamp, long receiveTimeNanos) {
        this(channel, variables, stamp, receiveTimeNanos, "", 0, 0);
    }

    DtronChannelValued(DtronChannel channel, Map<String, Integer> variables, Stamp stamp, long receiveTimeNanos,
            String text, long endTimeNanos, long dueTimeNanos) {
        this.channel = channel;
        this.variables = Collections.unmodifiableMap(new LinkedHashMap<>(variables));
        this.stamp = Objects.requireNonNull(stamp, "stamp");
        this.receiveTimeNanos = receiveTimeNanos;
        this.text = Objects.requireNonNull(text, "text");
        this.endTimeNanos = endTimeNanos;
        this.dueTimeNanos = dueTimeNanos;
    }

    /** Returns a message as this member published it: stamped, not received (receive time 0). */
    public static DtronChannelValued published(DtronChannel channel, Map<String, Integer> variables, Stamp stamp) {
        return published(channel, variables, stamp, "", 0, 0);
    }

    /**
     * Returns a message with a {@code text} (or ""), on a run start the announced end of the run (or 0), and on an
     * input sent ahead its due time (or 0), as this member published it.
     */
    public static DtronChannelValued published(DtronChannel channel, Map<String, Integer> variables, Stamp stamp,
            String text, long endTimeNanos, long dueTimeNanos) {
        Map<String, Integer> ordered = new LinkedHashMap<>();
        channel.getVariableNames().forEach(name -> ordered.put(name, variables.get(name)));
        variables.forEach(ordered::putIfAbsent);
        return new DtronChannelValued(channel, ordered, stamp, 0, text, endTimeNanos, dueTimeNanos);
    }

    @Override
    public String getText() {
        return text;
    }

    @Override
    public long getEndTimeNanos() {
        return endTimeNanos;
    }

    @Override
    public long getDueTimeNanos() {
        return dueTimeNanos;
    }

    /** Returns what the message carries besides its channel and variables, as on the wire. */
    public Stamp stamp() {
        return stamp;
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
        return stamp.sender();
    }

    @Override
    public long getSequence() {
        return stamp.sequence();
    }

    @Override
    public long getPublishTimeNanos() {
        return stamp.publishTimeNanos();
    }

    @Override
    public long getEventTimeNanos() {
        return stamp.effectiveEventTimeNanos();
    }

    @Override
    public long getReceiveTimeNanos() {
        return receiveTimeNanos;
    }

    @Override
    public String getRunId() {
        return stamp.runId();
    }

    @Override
    public String getAckedSender() {
        return stamp.ackedSender();
    }

    @Override
    public long getAckedSequence() {
        return stamp.ackedSequence();
    }

    @Override
    public long getClockOffsetNanos() {
        return stamp.clockOffsetNanos();
    }

    @Override
    public long getClockErrorNanos() {
        return stamp.clockErrorNanos();
    }

    @Override
    public byte[] toByteArray() {
        return SyncCodec.encode(getChannelName(), variables, stamp, text, endTimeNanos, dueTimeNanos);
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof DtronChannelValued other
                && channel.equals(other.channel)
                && variables.equals(other.variables)
                && stamp.equals(other.stamp)
                && receiveTimeNanos == other.receiveTimeNanos
                && text.equals(other.text)
                && endTimeNanos == other.endTimeNanos
                && dueTimeNanos == other.dueTimeNanos;
    }

    @Override
    public int hashCode() {
        return Objects.hash(channel, variables, stamp, receiveTimeNanos, text, endTimeNanos, dueTimeNanos);
    }

    @Override
    public String toString() {
        StringBuilder text = new StringBuilder(channel.getChannelName()).append(variables);
        if (!stamp.sender().isEmpty()) {
            text.append(" from ").append(stamp.sender()).append('#').append(stamp.sequence());
        }
        if (!stamp.ackedSender().isEmpty()) {
            text.append(" acknowledging ").append(stamp.ackedSender()).append('#').append(stamp.ackedSequence());
        }
        return text.toString();
    }
}
