package io.dtron.models;

import io.dtron.engine.TestClock;
import java.util.Comparator;
import java.util.PriorityQueue;

/**
 * A {@link TestClock} in virtual microseconds for tests: scheduled tasks wait in a priority queue (by due time,
 * then by the order they were scheduled in) and run only when the test advances the time.
 */
public final class VirtualClock implements TestClock {

    private static final class Task implements Scheduled {
        private final long due;
        private final long order;
        private final Runnable body;
        private boolean cancelled;

        private Task(long due, long order, Runnable body) {
            this.due = due;
            this.order = order;
            this.body = body;
        }

        @Override
        public void cancel() {
            cancelled = true;
        }
    }

    private final PriorityQueue<Task> queue =
            new PriorityQueue<>(Comparator.comparingLong((Task t) -> t.due).thenComparingLong(t -> t.order));
    private long now;
    private long scheduled;

    @Override
    public long nowMicros() {
        return now;
    }

    @Override
    public Scheduled schedule(long delayMicros, Runnable task) {
        if (delayMicros < 0) {
            throw new IllegalArgumentException("negative delay " + delayMicros);
        }
        Task t = new Task(now + delayMicros, scheduled++, task);
        queue.add(t);
        return t;
    }

    /** Runs, in order, every task due up to {@code micros} (including those they schedule), then sets the time. */
    public void advanceTo(long micros) {
        if (micros < now) {
            throw new IllegalArgumentException("time goes forward only: " + micros + " < " + now);
        }
        while (!queue.isEmpty() && queue.peek().due <= micros) {
            Task t = queue.poll();
            now = t.due;
            if (!t.cancelled) {
                t.body.run();
            }
        }
        now = micros;
    }
}
