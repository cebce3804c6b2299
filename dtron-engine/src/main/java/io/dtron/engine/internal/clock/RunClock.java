package io.dtron.engine.internal.clock;

import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import java.util.PriorityQueue;
import java.util.concurrent.LinkedBlockingQueue;
import org.slf4j.LoggerFactory;

/**
 * The clock of one run, as the tester drives it: scheduled tasks run on the tester's thread, inside
 * {@link #awaitUntil}, and outputs reported by adapters are queued with their times. Subclasses decide what
 * waiting means: virtual time jumps, real time sleeps.
 */
public abstract class RunClock implements TestClock {

    /**
     * What an adapter reported, with its time in microseconds since the start: an output (with {@code event}); the
     * adapter's report that the run cannot go on (with {@code abort}, the reason); or the acknowledgement that
     * input number {@code appliedInput} (1 for the first the engine performed) was applied at that time. An event
     * reported with an uncertainty happened within {@code uncertainty} microseconds of {@code micros}.
     */
    public record TimedEvent(Event event, long micros, String abort, long appliedInput, long uncertainty) {
        /** An output. */
        public TimedEvent(Event event, long micros) {
            this(event, micros, null, 0, 0);
        }
    }

    private final PriorityQueue<Task> tasks = new PriorityQueue<>();
    private final LinkedBlockingQueue<TimedEvent> outputs = new LinkedBlockingQueue<>();
    private long sequence;
    /** The due time of the task running now, or -1: its events and timers count from when it was due. */
    private volatile long taskTime = -1;

    private static final class Task implements Comparable<Task>, Scheduled {
        final long due;
        final long seq;
        final Runnable action;
        volatile boolean cancelled;

        Task(long due, long seq, Runnable action) {
            this.due = due;
            this.seq = seq;
            this.action = action;
        }

        @Override
        public int compareTo(Task o) {
            return due != o.due ? Long.compare(due, o.due) : Long.compare(seq, o.seq);
        }

        @Override
        public void cancel() {
            cancelled = true;
        }
    }

    @Override
    public final Scheduled schedule(long delayMicros, Runnable task) {
        synchronized (tasks) {
            Task t = new Task(logicalNow() + Math.max(0, delayMicros), sequence++, task);
            tasks.add(t);
            return t;
        }
    }

    /**
     * Queues an output reported now (thread-safe). Inside a scheduled task, "now" is the time the task was due,
     * so that a simulated system's timing does not depend on how busy the tester was.
     */
    public final void report(Event output) {
        synchronized (outputs) {
            outputs.add(new TimedEvent(output, logicalNow()));
        }
    }

    /**
     * Queues an output that happened at {@code micros}, as its adapter stamped it (thread-safe). It may be earlier
     * than outputs already queued: the tester places it by its time, within its reorder window.
     */
    public final void reportAt(Event output, long micros, long uncertainty) {
        synchronized (outputs) {
            outputs.add(new TimedEvent(output, micros, null, 0, uncertainty));
        }
    }

    /**
     * Queues the acknowledgement that input number {@code ordinal} was applied at {@code micros}, give or take
     * {@code uncertainty} (thread-safe).
     */
    public final void inputApplied(long ordinal, long micros, long uncertainty) {
        synchronized (outputs) {
            outputs.add(new TimedEvent(null, micros, null, ordinal, uncertainty));
        }
    }

    /** Queues the adapter's report that the run cannot go on (thread-safe). */
    public final void abort(String reason) {
        synchronized (outputs) {
            outputs.add(new TimedEvent(null, logicalNow(), reason, 0, 0));
        }
    }

    /** Whether the current wait is a loose one ({@link #awaitLooselyUntil}); the engine's thread alone waits. */
    private boolean loose;

    /**
     * The time now if no output is waiting, else -1. Atomic with {@link #report}: an output reported before is
     * waiting, one reported after carries this time or a later one (an output reported with its own earlier time,
     * {@link #reportAt}, is placed by the tester's reorder window). So a tester that acts at the time returned
     * never acts after an output it has not seen, however long a reporting thread was held up.
     */
    public final long quietNow() {
        synchronized (outputs) {
            return outputs.isEmpty() ? nowMicros() : -1;
        }
    }

    private long logicalNow() {
        long t = taskTime;
        return t >= 0 ? t : nowMicros();
    }

    /**
     * Runs due tasks and waits until {@code untilMicros} or until an output is reported, whichever comes first;
     * returns the output (removed from the queue), or null when the time was reached first: then every output
     * reported later carries a time at or after {@code untilMicros}.
     */
    public final TimedEvent awaitUntil(long untilMicros) {
        while (true) {
            TimedEvent output = outputs.poll();
            if (output != null) {
                return output;
            }
            Task next;
            synchronized (tasks) {
                next = tasks.peek();
            }
            long target = next == null ? untilMicros : Math.min(untilMicros, next.due);
            if (!waitFor(target)) {
                continue;
            }
            if (next != null && next.due <= target && nowMicros() >= next.due) {
                synchronized (tasks) {
                    tasks.remove(next);
                }
                if (!next.cancelled) {
                    taskTime = next.due;
                    try {
                        next.action.run();
                    } catch (RuntimeException | AssertionError e) {
                        // a task is the adapter's (the system under test's): its exception ends the run, not DTRON
                        abort(thrown("a task of the system under test", e));
                    } finally {
                        taskTime = -1;
                    }
                }
                continue;
            }
            if (nowMicros() >= untilMicros) {
                // null only when quiet (atomic with reports): a later output carries a time past untilMicros
                return quietNow() >= 0 ? null : outputs.poll();
            }
        }
    }

    /**
     * Waits as {@link #awaitUntil} does, but the time need not be met to the millisecond: a real clock sleeps the
     * whole wait (spinning none of it) and does not count how late it woke up. For a tester that waits for the time
     * of an input it already sent ahead: its adapter keeps that time, and the spin would only take a CPU from it.
     */
    public final TimedEvent awaitLooselyUntil(long untilMicros) {
        loose = true;
        try {
            return awaitUntil(untilMicros);
        } finally {
            loose = false;
        }
    }

    /** Whether the current wait need not meet its time precisely ({@link #awaitLooselyUntil}). */
    protected final boolean loose() {
        return loose;
    }

    /**
     * Runs the tasks already due and returns the first output waiting (removed from the queue), or null: what
     * happened before now must be seen before the tester acts at a late time.
     */
    public final TimedEvent drain() {
        return awaitUntil(nowMicros());
    }

    /**
     * How late, at most, a wait of this clock has ended after its target so far, in microseconds: the scheduling delay
     * of the tester's thread in real time; 0 in virtual time.
     */
    public long worstLatenessMicros() {
        return 0;
    }

    /**
     * Sets time 0; called once, right before the adapter starts. In real time, time 0 is {@code zeroNanoTime} (a
     * {@link System#nanoTime()} reading) if given, waiting for it if it lies ahead, else now; virtual time starts at
     * 0 anyway.
     */
    public void begin(java.util.OptionalLong zeroNanoTime) {
    }

    /**
     * What an exception thrown by the adapter's code says to a user, on one line and without its stack trace (logged
     * at debug): {@code WHO threw IllegalStateException: its message, at Sut.perform(Sut.java:12)}.
     */
    public static String thrown(String who, Throwable e) {
        LoggerFactory.getLogger(RunClock.class).debug(who + " threw", e);
        StackTraceElement[] frames = e.getStackTrace();
        String message = e.getMessage() == null ? "" : ": " + e.getMessage().strip().replaceAll("\\s*\\R\\s*", " ");
        return who + " threw " + e.getClass().getSimpleName() + message + (frames.length == 0 ? "" : ", at "
                + frames[0]);
    }

    /** Whether an output is waiting. */
    protected final boolean hasOutput() {
        return !outputs.isEmpty();
    }

    /**
     * Moves or waits the time forward to {@code targetMicros}; returns false if an output arrived first (then
     * the time may be earlier than the target).
     */
    protected abstract boolean waitFor(long targetMicros);

    /** Blocks until an output arrives or {@code nanos} pass; for real time. */
    protected final void awaitOutput(long nanos) throws InterruptedException {
        TimedEvent e = outputs.poll(nanos, java.util.concurrent.TimeUnit.NANOSECONDS);
        if (e != null) {
            outputs.add(e);
        }
    }
}
