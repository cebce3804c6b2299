package io.dtron.api.internal;

import java.time.Duration;
import java.util.ArrayDeque;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. Runs tasks one after another, in submission order, on one daemon
 * thread of its own, so that listeners see messages in the bus's order while
 * the transport's threads never wait for them.
 *
 * <p>{@link #runOrExecute} is the fast path of a task that may run on the
 * caller's thread: when no task runs and none is queued, it runs the task at
 * once on the caller's thread (sparing the wake-up of this executor's thread,
 * which on a virtual machine with idle CPUs costs milliseconds); otherwise it
 * queues it. Either way the tasks still run one at a time, in submission order:
 * a task submitted while one runs inline is queued behind it, also from the
 * inline task itself (a task never runs nested in another).
 */
public final class SerialExecutor {
    private static final Logger LOG = LoggerFactory.getLogger(SerialExecutor.class);

    /** Guarded by {@code this}: the tasks waiting to run. */
    private final ArrayDeque<Runnable> queue = new ArrayDeque<>();
    private final Thread thread;
    /** Guarded by {@code this}: whether a task runs, on this executor's thread or inline on another. */
    private boolean running;
    /** Guarded by {@code this}: set by {@link #shutdown}; no task is taken after. */
    private boolean stopping;
    /** The thread that runs a task inline now, or null. */
    private volatile Thread inlineRunner;

    /** Starts the thread. */
    public SerialExecutor(String threadName) {
        thread = new Thread(this::run, threadName);
        thread.setDaemon(true);
        thread.start();
    }

    /** Queues a task for this executor's thread; ignored once {@link #shutdown} was called. */
    public void execute(Runnable task) {
        synchronized (this) {
            if (!stopping) {
                queue.add(task);
                notifyAll();
            }
        }
    }

    /**
     * Runs a task on the caller's thread at once when no task runs and none is queued (and {@link #shutdown} was
     * not called), else queues it as {@link #execute} does. While it runs inline, tasks submitted meanwhile queue
     * behind it and {@link #inExecutorThread()} is true on the caller's thread.
     *
     * @return whether the task ran on the caller's thread
     */
    public boolean runOrExecute(Runnable task) {
        synchronized (this) {
            if (stopping) {
                return false;
            }
            if (running || !queue.isEmpty()) {
                queue.add(task);
                notifyAll();
                return false;
            }
            running = true;
        }
        inlineRunner = Thread.currentThread();
        try {
            runTask(task);
        } finally {
            inlineRunner = null;
            synchronized (this) {
                running = false;
                notifyAll();
            }
        }
        return true;
    }

    /**
     * From a task that runs inline ({@link #runOrExecute}): queues {@code rest} to run on this executor's thread
     * right after the current task, ahead of the tasks queued meanwhile, so that it keeps the current task's
     * place in the order. Runs after {@link #shutdown} too, as a queued task does.
     *
     * @throws IllegalStateException if the caller does not run a task inline
     */
    public void continueOnOwnThread(Runnable rest) {
        if (!runsInline()) {
            throw new IllegalStateException("not in a task that runs inline");
        }
        synchronized (this) {
            queue.addFirst(rest);
            notifyAll();
        }
    }

    /**
     * Waits until the tasks queued before this call have run, at most {@code timeout}; returns at once in a task of
     * this executor (they have run by the time the current task ends) and once {@link #shutdown} was called.
     *
     * @return whether they have run (or run before the caller's task, on this thread)
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean awaitQueued(Duration timeout) throws InterruptedException {
        if (inExecutorThread()) {
            return true;
        }
        CountDownLatch passed = new CountDownLatch(1);
        execute(passed::countDown);
        return !isStopping() && passed.await(timeout.toNanos(), TimeUnit.NANOSECONDS);
    }

    /** Returns whether the caller runs a task of this executor: on its thread, or inline ({@link #runOrExecute}). */
    public boolean inExecutorThread() {
        return Thread.currentThread() == thread || runsInline();
    }

    /** Returns whether the caller runs a task of this executor inline, on a thread other than the executor's. */
    public boolean runsInline() {
        return Thread.currentThread() == inlineRunner;
    }

    /**
     * Runs the tasks queued so far, then stops the thread; a task that runs inline meanwhile finishes. Waits for
     * both at most {@code timeout}, and not at all when called from a task.
     *
     * @return whether the thread has stopped and no task runs inline
     */
    public boolean shutdown(Duration timeout) {
        synchronized (this) {
            stopping = true;
            notifyAll();
        }
        if (inExecutorThread()) {
            return false;
        }
        try {
            // the thread stops only when no task runs inline either, and none can start after this call
            thread.join(timeout.toMillis());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        return !thread.isAlive();
    }

    private synchronized boolean isStopping() {
        return stopping;
    }

    private void run() {
        while (true) {
            Runnable task;
            synchronized (this) {
                while (running || queue.isEmpty()) {
                    if (stopping && queue.isEmpty() && !running) {
                        return; // not while a task runs inline: it may still queue its continuation
                    }
                    try {
                        wait();
                    } catch (InterruptedException e) {
                        return;
                    }
                }
                task = queue.poll();
                running = true;
            }
            try {
                runTask(task);
            } finally {
                synchronized (this) {
                    running = false;
                    notifyAll();
                }
            }
        }
    }

    private void runTask(Runnable task) {
        try {
            task.run();
        } catch (RuntimeException e) {
            LOG.error("Task failed on {}", Thread.currentThread().getName(), e);
        }
    }
}
