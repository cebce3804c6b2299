package io.dtron.bridge.internal;

import io.dtron.api.IDtronChannelValued;
import java.util.OptionalLong;
import java.util.function.LongSupplier;

/**
 * Not API. The one place where a bus run converts time: time 0 of the run on the tester's wall clock, and the times
 * of the run's messages on the run's clock in microseconds since time 0 (an event's time as its sender stamped it,
 * corrected by the sender's clock offset; a message's receive time; an input's publish time). In a run of several
 * testers also time 0 as a {@link System#nanoTime()} reading, for the engine to start at. Thread-safe.
 */
public final class RunTimeline {
    private final LongSupplier wallClock;
    /** The tester's wall-clock time of the run's time 0, in nanoseconds since the epoch. */
    private volatile long zeroEpochNanos;
    /** Whether time 0 was set before the engine started (a run of several testers). */
    private volatile boolean announced;
    /** The run's time 0 as a {@link System#nanoTime()} reading, when announced. */
    private volatile long zeroNanoTime;

    /** @param wallClock this member's wall clock in nanoseconds since the epoch, as it stamps messages */
    public RunTimeline(LongSupplier wallClock) {
        this.wallClock = wallClock;
    }

    /**
     * Sets time 0 as the engine started: {@code runMicros} on the engine's clock is {@code nowEpochNanos} on the
     * run's (the tester's) wall clock.
     *
     * @return time 0 on the run's wall clock, in nanoseconds since the epoch
     */
    public long startedAt(long nowEpochNanos, long runMicros) {
        zeroEpochNanos = nowEpochNanos - runMicros * 1000;
        return zeroEpochNanos;
    }

    /** Returns time 0 on the run's wall clock, in nanoseconds since the epoch. */
    public long zeroEpochNanos() {
        return zeroEpochNanos;
    }

    /**
     * Returns {@code runMicros} on the run's clock as a time on the run's wall clock, in nanoseconds since the epoch.
     */
    public long epochNanos(long runMicros) {
        return zeroEpochNanos + Math.multiplyExact(runMicros, 1000L);
    }

    /**
     * A run of several testers: time 0 is {@code zeroEpochNanos} on this member's wall clock, before the engine
     * starts; {@link #timeZero()} names it until {@link #takeAnnounced()}.
     */
    public void announce(long zeroEpochNanos) {
        zeroNanoTime = System.nanoTime() + (zeroEpochNanos - wallClock.getAsLong());
        announced = true;
    }

    /**
     * A joining tester: time 0 of the run the {@code start} message opened, on this member's wall clock, whose
     * offset to the run's clock is {@code ownOffsetNanos}.
     */
    public static long zeroOf(IDtronChannelValued start, long ownOffsetNanos) {
        return start.getEventTimeNanos() + start.getClockOffsetNanos() - ownOffsetNanos;
    }

    /** Time 0 as a {@link System#nanoTime()} reading when it was {@linkplain #announce announced}; else empty. */
    public OptionalLong timeZero() {
        long zero = zeroNanoTime;
        return announced ? OptionalLong.of(zero) : OptionalLong.empty();
    }

    /** Whether time 0 was announced before the engine started; clears it for the next run. */
    public boolean takeAnnounced() {
        boolean was = announced;
        announced = false;
        return was;
    }

    /** The time of an event on the run's clock, in microseconds: its sender's time corrected by its offset. */
    public long eventMicros(IDtronChannelValued message) {
        long testerNanos = message.getEventTimeNanos() + message.getClockOffsetNanos();
        return Math.floorDiv(testerNanos - zeroEpochNanos, 1000);
    }

    /** When a message arrived here, on the run's clock in microseconds. */
    public long receivedMicros(IDtronChannelValued message) {
        return Math.floorDiv(message.getReceiveTimeNanos() - zeroEpochNanos, 1000);
    }

    /** When this member published a message, on the run's clock in microseconds. */
    public long publishedMicros(IDtronChannelValued published) {
        return Math.floorDiv(published.getPublishTimeNanos() - zeroEpochNanos, 1000);
    }

    /** How long after its event, at {@code eventRunMicros} on the run's clock, a message arrived, in microseconds. */
    public long arrivalDelay(IDtronChannelValued message, long eventRunMicros) {
        return Math.max(0, receivedMicros(message) - eventRunMicros);
    }

    /** A message's clock error bound in whole microseconds, rounded up: the uncertainty of its event time. */
    public static long errorMicros(IDtronChannelValued message) {
        return -Math.floorDiv(-message.getClockErrorNanos(), 1000);
    }
}
