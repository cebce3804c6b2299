package io.dtron.api.internal;

import io.dtron.api.DtronStats;
import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.bus.internal.DropReason;
import java.util.EnumMap;
import java.util.Map;
import java.util.concurrent.atomic.LongAdder;

/** Not API. The thread-safe counters of one Dtron. */
public final class Counters {
    private final LongAdder published = new LongAdder();
    private final LongAdder accepted = new LongAdder();
    private final Map<Reason, LongAdder> rejected = new EnumMap<>(Reason.class);
    private final LongAdder listenerFailures = new LongAdder();

    /** Creates counters at 0. */
    public Counters() {
        for (Reason reason : Reason.values()) {
            rejected.put(reason, new LongAdder());
        }
    }

    /** Counts a published message. */
    public void published() {
        published.increment();
    }

    /** Counts a valid received message. */
    public void accepted() {
        accepted.increment();
    }

    /** Counts a rejected received message. */
    public void rejected(Reason reason) {
        rejected.get(reason).increment();
    }

    /** Counts an exception thrown by a listener. */
    public void listenerFailed() {
        listenerFailures.increment();
    }

    /** Returns the current counts, with the messages the transport dropped ({@code drops}) as rejected. */
    public DtronStats snapshot(Map<DropReason, Long> drops) {
        Map<Reason, Long> rejectedCounts = new EnumMap<>(Reason.class);
        rejected.forEach((reason, count) -> rejectedCounts.put(reason, count.sum()));
        drops.forEach((reason, count) -> rejectedCounts.merge(Reason.valueOf(reason.name()), count, Long::sum));
        return new DtronStats(published.sum(), accepted.sum(), rejectedCounts, listenerFailures.sum());
    }
}
