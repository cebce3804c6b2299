package io.dtron.api;

import io.dtron.bus.internal.EpochClock;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.PriorityQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;
import java.util.function.LongSupplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The time of the current test run on the tester's clock, for an adapter whose system acts on its own (a ticker, a
 * timeout): one per {@link Dtron}, from {@link Dtron#runClock()}.
 *
 * <p>Time 0 of a run is the event time of its {@link Dtron#RUN_START} on the tester's clock. The run clock reads
 * this member's wall clock plus its {@linkplain Dtron#getClockOffsetNanos() estimated offset} to the tester's, so
 * that "at 10 time units" means the tester's 10 units even when {@code RUN_START} arrived late here. After
 * {@code RUN_START} arrived it advances with {@link System#nanoTime()}, so wall-clock steps do not move it; it never
 * goes back, and it follows a better offset estimate when one comes.
 *
 * <p>The clock starts when {@code RUN_START} arrives from the bus, before any listener hears of it (in a
 * {@code RUN_START} listener it already runs for that run), and stops when {@link Dtron#RUN_STOP} arrives, when the
 * run's tester leaves the bus, or when the {@code Dtron} closes. Tasks scheduled on it run at their run time on one
 * thread the clock owns, one after another; they belong to the run during which they were scheduled and are
 * cancelled when it stops or another starts. Thread-safe.
 */
public final class RunClock {
    private static final Logger LOG = LoggerFactory.getLogger(RunClock.class);

    /** A task scheduled on a {@link RunClock}. */
    public interface Task {
        /**
         * Cancels the task: it runs no more (a run already under way finishes).
         *
         * @return whether it was still scheduled
         */
        boolean cancel();

        /** Returns whether the task was cancelled, by {@link #cancel()} or because its run stopped. */
        boolean isCancelled();
    }

    /**
     * How long before a task's time the clock's thread stops waiting and spins: a timed wait of this machine's
     * threads may end milliseconds late when its CPU was idle, a spin of this length does not.
     */
    private static final long SPIN_NANOS = 1_000_000;
    /** The longest an input sent ahead is held ({@link #runAt}): a tester sends inputs milliseconds ahead. */
    private static final long MAX_HOLD_NANOS = 1_000_000_000;
    /** How often a thread waiting in {@link #runAt} looks whether its task was cancelled (the run stopped). */
    private static final long HOLD_CHECK_NANOS = 10_000_000;
    /** How far ahead the warm-up ({@link #warmUp}) hands a task to {@link #runAt}. */
    private static final long RUN_AT_WARM_UP_NANOS = 2_000_000;

    private final String member;
    private final LongSupplier wallClock;
    private final LongSupplier offset;
    private final ReentrantLock lock = new ReentrantLock();
    private final Condition changed = lock.newCondition();
    private final PriorityQueue<Entry> queue = new PriorityQueue<>();
    private final Thread thread;
    private Entry executing;
    private volatile boolean closed;
    /** Counts the signals of {@link #changed}, so that a spinning thread sees them too. */
    private volatile int changes;
    private final AtomicLong entries = new AtomicLong();
    // the current or last run, written with the lock held and read without it
    private volatile Run run;

    /** One run: time 0 on the tester's clock, and this member's wall clock and nanoTime read together. */
    private record Run(long generation, boolean running, long testerTimeZero, long timeUnitMicros, String runId,
            long wallBase, long nanoBase, AtomicLong latest) {
        Run stopped() {
            return new Run(generation, false, testerTimeZero, timeUnitMicros, runId, wallBase, nanoBase, latest);
        }
    }

    private final class Entry implements Task, Comparable<Entry> {
        private final Runnable action;
        private final long generation;
        private final long periodNanos;
        private final long order = entries.incrementAndGet();
        private final AtomicBoolean cancelled = new AtomicBoolean();
        private long due;

        Entry(Runnable action, long generation, long due, long periodNanos) {
            this.action = action;
            this.generation = generation;
            this.due = due;
            this.periodNanos = periodNanos;
        }

        @Override
        public boolean cancel() {
            boolean was = cancelled.compareAndSet(false, true);
            if (was) {
                lock.lock();
                try {
                    queue.remove(this);
                    signalChanged();
                } finally {
                    lock.unlock();
                }
            }
            return was;
        }

        @Override
        public boolean isCancelled() {
            return cancelled.get();
        }

        @Override
        public int compareTo(Entry other) {
            int byDue = Long.compare(due, other.due);
            return byDue != 0 ? byDue : Long.compare(order, other.order);
        }

        @Override
        public String toString() {
            return "task at run time " + due + " ns" + (periodNanos > 0 ? " every " + periodNanos + " ns" : "");
        }
    }

    /**
     * @param member    the member's id, for the thread's name
     * @param wallClock the member's wall clock, ns since the epoch
     * @param offset    the current estimate of (tester's clock - own clock), 0 if none
     */
    RunClock(String member, LongSupplier wallClock, LongSupplier offset) {
        this.member = member;
        this.wallClock = wallClock;
        this.offset = offset;
        // started now, not by the first task of a run, when the adapter may have a few milliseconds to act
        this.thread = new Thread(this::loop, "dtron-run-clock-" + member);
        thread.setDaemon(true);
        thread.start();
    }

    /** Returns whether a run is under way: its {@code RUN_START} arrived, and it has not stopped. */
    public boolean isRunning() {
        Run current = run;
        return current != null && current.running();
    }

    /** Returns the time unit of the current (or else the last) run in microseconds; 0 if no run started yet. */
    public long timeUnitMicros() {
        Run current = run;
        return current == null ? 0 : current.timeUnitMicros();
    }

    /** Returns the id of the current (or else the last) run as its {@code RUN_START} carried it, or "". */
    public String runId() {
        Run current = run;
        return current == null ? "" : current.runId();
    }

    /**
     * Returns the time in nanoseconds since time 0 of the current (or else the last) run, on the tester's clock as
     * estimated here. Never less than a value it returned before in the same run.
     *
     * @throws IllegalStateException if no run started yet
     */
    public long nowNanos() {
        return now(requireStarted());
    }

    /**
     * Returns {@link #nowNanos()} in the run's time units.
     *
     * @throws IllegalStateException if no run started yet
     */
    public double nowUnits() {
        Run current = requireStarted();
        return now(current) / (current.timeUnitMicros() * 1_000.0);
    }

    /**
     * Returns when a message's event happened in run time (ns since time 0 of the current or else the last run):
     * its {@linkplain IDtronChannelValued#getEventTimeNanos() event time} plus the
     * {@linkplain IDtronChannelValued#getClockOffsetNanos() clock offset} it carries (0 from the tester) minus time
     * 0. For an input from the tester this is when the tester published it.
     *
     * @throws IllegalStateException if no run started yet
     */
    public long runNanosOf(IDtronChannelValued message) {
        Objects.requireNonNull(message, "message");
        Run current = requireStarted();
        return message.getEventTimeNanos() + message.getClockOffsetNanos() - current.testerTimeZero();
    }

    /**
     * Runs a task once, at a run time in the run's time units (not a delay: at 10.0 the task runs when the
     * tester's clock shows 10 units since time 0). A time already past runs it at once.
     *
     * @return the scheduled task; if no run is under way, a task that is already cancelled and never runs
     * @throws IllegalArgumentException if the time is not finite
     */
    public Task scheduleAt(double runUnits, Runnable task) {
        Objects.requireNonNull(task, "task");
        Run current = run;
        if (current == null || !current.running()) {
            return notScheduled(task);
        }
        return schedule(task, current, unitsToNanos(runUnits, current), 0);
    }

    /**
     * Runs a task once, at a run time in nanoseconds since time 0 of the run. A time already past runs it at once.
     *
     * @return the scheduled task; if no run is under way, a task that is already cancelled and never runs
     */
    public Task scheduleAtNanos(long runNanos, Runnable task) {
        Objects.requireNonNull(task, "task");
        Run current = run;
        if (current == null || !current.running()) {
            return notScheduled(task);
        }
        return schedule(task, current, runNanos, 0);
    }

    /**
     * Runs a task at run times {@code first}, {@code first + period}, {@code first + 2 * period}, ... (in the run's
     * time units) until it is cancelled or the run stops. The times do not drift: a late run does not delay the
     * next ones, and runs whose time has passed (after a long task, or when scheduled late) run at once, in order.
     *
     * @return the scheduled task; if no run is under way, a task that is already cancelled and never runs
     * @throws IllegalArgumentException if the period is not positive (or shorter than a nanosecond) or a value is
     *                                  not finite
     */
    public Task scheduleAtFixedRate(double firstUnits, double periodUnits, Runnable task) {
        Objects.requireNonNull(task, "task");
        Run current = run;
        if (current == null || !current.running()) {
            return notScheduled(task);
        }
        long period = unitsToNanos(periodUnits, current);
        if (period <= 0) {
            throw new IllegalArgumentException("period must be positive: " + periodUnits);
        }
        return schedule(task, current, unitsToNanos(firstUnits, current), period);
    }

    @Override
    public String toString() {
        Run current = run;
        return "RunClock[" + member + (current == null ? ", no run yet]"
                : ", run " + current.generation() + (current.running() ? " running" : " stopped")
                        + ", unit " + current.timeUnitMicros() + " us]");
    }

    // ---- called by Dtron

    /**
     * Runs a clock of its own through a run: started, read, tasks scheduled and cancelled, one run on its thread and
     * one handed to it ({@link #runAt}), stopped and closed. So a fresh process loads and first runs this code when it
     * joins the bus, not at time 0 of its first run, when an adapter may have a few milliseconds to act. Waits at most
     * {@code limit} for the task; touches no other clock.
     */
    static void warmUp(Duration limit) {
        RunClock clock = new RunClock("warm-up", EpochClock::nowNanos, () -> 0);
        try {
            clock.start(EpochClock.nowNanos(), 1_000, "");
            clock.nowUnits();
            clock.scheduleAt(1e9, () -> { }).cancel();
            clock.scheduleAtFixedRate(1e9, 1, () -> { }).cancel();
            CountDownLatch ran = new CountDownLatch(1);
            clock.scheduleAt(0, ran::countDown);
            ran.await(limit.toNanos(), TimeUnit.NANOSECONDS);
            clock.runAt(EpochClock.nowNanos() + RUN_AT_WARM_UP_NANOS, () -> { });
            clock.stop();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } finally {
            clock.close();
        }
    }

    /** A run started: its time 0 on the tester's clock. Cancels the tasks of the one before. */
    void start(long testerTimeZero, long timeUnitMicros, String runId) {
        lock.lock();
        try {
            if (closed) {
                return;
            }
            Run previous = run;
            long generation = previous == null ? 1 : previous.generation() + 1;
            long nanoBase = System.nanoTime();
            long wallBase = wallClock.getAsLong();
            run = new Run(generation, true, testerTimeZero, timeUnitMicros, runId, wallBase, nanoBase,
                    new AtomicLong(Long.MIN_VALUE));
            cancelAll();
        } finally {
            lock.unlock();
        }
        if (timeUnitMicros <= 0) {
            LOG.warn("The run started with time unit {} us; the run clock cannot count in units", timeUnitMicros);
        }
    }

    /** The run stopped: its tasks are cancelled. */
    void stop() {
        lock.lock();
        try {
            Run current = run;
            if (current != null && current.running()) {
                run = current.stopped();
            }
            cancelAll();
        } finally {
            lock.unlock();
        }
    }

    /**
     * Runs {@code task} on the clock's thread when the tester's clock, as estimated here, reads {@code dueEpochNanos}
     * (the tester's wall clock, in nanoseconds since the epoch) in the current run, and waits until it has run: an
     * input its tester sent ahead of its time is handed to the listeners then, from the thread that spins the last
     * millisecond before its tasks (a thread woken from a timed wait may come milliseconds late), while what follows
     * it waits behind. Runs it at once on the calling thread when the time has passed or no run is under way, and
     * when the run stops or {@value #MAX_HOLD_NANOS} ns have passed before it ran.
     */
    void runAt(long dueEpochNanos, Runnable task) {
        Run current = run;
        if (current == null || !current.running() || Thread.currentThread() == thread) {
            task.run();
            return;
        }
        AtomicBoolean claimed = new AtomicBoolean();
        CountDownLatch ran = new CountDownLatch(1);
        Task scheduled = schedule(() -> {
            if (claimed.compareAndSet(false, true)) {
                try {
                    task.run();
                } finally {
                    ran.countDown();
                }
            }
        }, current, dueEpochNanos - current.testerTimeZero(), 0);
        long limit = System.nanoTime() + MAX_HOLD_NANOS;
        boolean interrupted = false;
        while (ran.getCount() > 0 && !scheduled.isCancelled() && System.nanoTime() < limit) {
            try {
                ran.await(HOLD_CHECK_NANOS, TimeUnit.NANOSECONDS);
            } catch (InterruptedException e) {
                interrupted = true;
                break;
            }
        }
        scheduled.cancel();
        if (claimed.compareAndSet(false, true)) {
            task.run(); // the run stopped, or the clock's thread did not come to it in time
        } else {
            ranUninterruptibly(ran);
        }
        if (interrupted) {
            Thread.currentThread().interrupt();
        }
    }

    private static void ranUninterruptibly(CountDownLatch ran) {
        boolean interrupted = false;
        while (ran.getCount() > 0) {
            try {
                ran.await();
            } catch (InterruptedException e) {
                interrupted = true;
            }
        }
        if (interrupted) {
            Thread.currentThread().interrupt();
        }
    }

    /** The offset estimate changed: pending tasks are due at other wall-clock times. */
    void offsetChanged() {
        lock.lock();
        try {
            signalChanged();
        } finally {
            lock.unlock();
        }
    }

    /** Stops the run and the thread. */
    void close() {
        lock.lock();
        try {
            stop();
            closed = true;
            signalChanged();
        } finally {
            lock.unlock();
        }
        if (thread != Thread.currentThread()) {
            try {
                thread.join(TimeUnit.SECONDS.toMillis(5));
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
    }

    // ---- internals

    private Run requireStarted() {
        Run current = run;
        if (current == null) {
            throw new IllegalStateException("no run has started yet");
        }
        return current;
    }

    private long now(Run current) {
        long raw = current.wallBase() + (System.nanoTime() - current.nanoBase()) + offset.getAsLong()
                - current.testerTimeZero();
        return current.latest().accumulateAndGet(raw, Math::max);
    }

    private static long unitsToNanos(double units, Run current) {
        if (!Double.isFinite(units)) {
            throw new IllegalArgumentException("not a finite number of time units: " + units);
        }
        if (current.timeUnitMicros() <= 0) {
            throw new IllegalStateException("the run's time unit is " + current.timeUnitMicros() + " us");
        }
        return Math.round(units * current.timeUnitMicros() * 1_000.0);
    }

    private Task notScheduled(Runnable task) {
        LOG.debug("No run under way on {}; {} not scheduled", member, task);
        Entry entry = new Entry(task, 0, 0, 0);
        entry.cancelled.set(true);
        return entry;
    }

    private Task schedule(Runnable task, Run current, long due, long period) {
        lock.lock();
        try {
            Entry entry = new Entry(task, current.generation(), due, period);
            if (closed || run != current) {
                entry.cancelled.set(true);
                return entry;
            }
            queue.add(entry);
            signalChanged();
            return entry;
        } finally {
            lock.unlock();
        }
    }

    /** Called with the lock held. */
    private void cancelAll() {
        List<Entry> pending = new ArrayList<>(queue);
        queue.clear();
        pending.forEach(entry -> entry.cancelled.set(true));
        if (executing != null && executing.periodNanos > 0) {
            executing.cancelled.set(true); // runs to its end, and no more
        }
        signalChanged();
    }

    private void loop() {
        lock.lock();
        try {
            while (!closed) {
                Entry next = queue.peek();
                Run current = run;
                if (next == null || current == null || !current.running()) {
                    changed.awaitUninterruptibly();
                    continue;
                }
                long wait = next.due - now(current);
                if (wait > SPIN_NANOS) {
                    changed.awaitNanos(wait - SPIN_NANOS);
                    continue;
                }
                if (wait > 0) {
                    // a timed wait here wakes up to milliseconds late (an idle CPU of a virtual machine): the last
                    // stretch is spun, with the lock let go so that tasks can be scheduled and cancelled meanwhile
                    int seen = changes;
                    lock.unlock();
                    try {
                        spinUntil(next.due, current, seen);
                    } finally {
                        lock.lock();
                    }
                    continue;
                }
                queue.poll();
                if (next.isCancelled() || next.generation != current.generation()) {
                    next.cancelled.set(true);
                    continue;
                }
                executing = next;
                lock.unlock();
                try {
                    runTask(next);
                } finally {
                    lock.lock();
                    executing = null;
                }
                if (next.periodNanos > 0) {
                    if (!next.isCancelled() && !closed && run == current) {
                        next.due += next.periodNanos;
                        queue.add(next);
                    } else {
                        // the run stopped (or another started) while it ran: it was out of the queue then
                        next.cancelled.set(true);
                    }
                }
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } finally {
            lock.unlock();
        }
    }

    /** Called with the lock held: wakes the clock's thread, waiting or spinning. */
    private void signalChanged() {
        changes++;
        changed.signalAll();
    }

    /**
     * Spins until run time {@code dueNanos} of {@code current}, or until the queue, the run or the offset changed
     * since {@code seen} was read.
     */
    private void spinUntil(long dueNanos, Run current, int seen) {
        while (changes == seen && now(current) < dueNanos) {
            Thread.onSpinWait();
        }
    }

    private void runTask(Entry entry) {
        try {
            entry.action.run();
        } catch (VirtualMachineError e) {
            throw e;
        } catch (Throwable e) {
            LOG.error("Run clock task {} of {} failed", entry.action, member, e);
        }
    }
}
