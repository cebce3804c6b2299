package io.dtron.api;

import io.dtron.api.InvalidMessageException.Reason;
import java.util.EnumMap;
import java.util.Locale;
import java.util.Map;
import java.util.Objects;

/**
 * What one {@link Dtron} has done so far: an immutable snapshot of its counters. They count channel messages,
 * {@link Dtron#RUN_START} and {@link Dtron#RUN_STOP} included; acknowledgements ({@link Dtron#ACK}) and the
 * messages by which members estimate their clock offsets are not counted. Messages the bus dropped because they
 * carry no valid code of the bus's secret ({@link Reason#UNAUTHENTICATED}, {@link Reason#REPLAYED},
 * {@link Reason#STALE}) are counted as rejected whatever they are, since nothing of them can be trusted.
 */
public final class DtronStats {
    private final long published;
    private final long accepted;
    private final Map<Reason, Long> rejected;
    private final long listenerFailures;

    /**
     * Creates a snapshot.
     *
     * @param published        messages this member published
     * @param accepted         valid messages received on channels known here
     * @param rejected         received messages rejected, by reason (reasons left out count 0)
     * @param listenerFailures exceptions thrown by listeners
     */
    public DtronStats(long published, long accepted, Map<Reason, Long> rejected, long listenerFailures) {
        this.published = published;
        this.accepted = accepted;
        EnumMap<Reason, Long> counts = new EnumMap<>(Reason.class);
        for (Reason reason : Reason.values()) {
            counts.put(reason, rejected.getOrDefault(reason, 0L));
        }
        this.rejected = Map.copyOf(counts);
        this.listenerFailures = listenerFailures;
    }

    /** Returns how many messages this member published. */
    public long getPublished() {
        return published;
    }

    /** Returns how many valid messages this member received on channels known to it. */
    public long getAccepted() {
        return accepted;
    }

    /** Returns how many received messages were rejected for a reason. */
    public long getRejected(Reason reason) {
        return rejected.get(Objects.requireNonNull(reason, "reason"));
    }

    /** Returns how many received messages were rejected for any reason. */
    public long getRejectedTotal() {
        return rejected.values().stream().mapToLong(Long::longValue).sum();
    }

    /** Returns how many times a listener threw an exception. */
    public long getListenerFailures() {
        return listenerFailures;
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof DtronStats other
                && published == other.published
                && accepted == other.accepted
                && rejected.equals(other.rejected)
                && listenerFailures == other.listenerFailures;
    }

    @Override
    public int hashCode() {
        return Objects.hash(published, accepted, rejected, listenerFailures);
    }

    @Override
    public String toString() {
        StringBuilder text = new StringBuilder("published ").append(published)
                .append(", accepted ").append(accepted)
                .append(", rejected ").append(getRejectedTotal());
        String separator = " (";
        for (Reason reason : Reason.values()) {
            long count = rejected.get(reason);
            if (count > 0) {
                text.append(separator).append(reason.name().toLowerCase(Locale.ROOT).replace('_', ' '))
                        .append(' ').append(count);
                separator = ", ";
            }
        }
        if (!separator.equals(" (")) {
            text.append(')');
        }
        return text.append(", listener failures ").append(listenerFailures).toString();
    }
}
