package io.dtron.api.internal;

import java.time.Duration;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. Runs tasks one after another, in submission order, on one daemon
 * thread of its own, so that listeners see messages in the bus's order while
 * the transport's threads never wait for them.
 */
public final class SerialExecutor {
    private static final Logger LOG = LoggerFactory.getLogger(SerialExecutor.class);
    private static final Runnable STOP = () -> { };

    private final BlockingQueue<Runnable> queue = new LinkedBlockingQueue<>();
    private final Thread thread;
    private volatile boolean stopping;

    /** Starts the thread. */
    public SerialExecutor(String threadName) {
        thread = new Thread(this::run, threadName);
        thread.setDaemon(true);
        thread.start();
    }

    /** Queues a task; ignored once {@link #shutdown} was called. */
    public void execute(Runnable task) {
        if (!stopping) {
            queue.add(task);
        }
    }

    /**
     * Waits until the tasks queued before this call have run, at most {@code timeout}; returns at once on this
     * executor's own thread (they have run by the time its current task ends) and once {@link #shutdown} was called.
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
        return !stopping && passed.await(timeout.toNanos(), TimeUnit.NANOSECONDS);
    }

    /** Returns whether the caller runs on this executor's thread. */
    public boolean inExecutorThread() {
        return Thread.currentThread() == thread;
    }

    /**
     * Runs the tasks queued so far, then stops the thread. Waits for that at
     * most {@code timeout}, and not at all when called from a task.
     *
     * @return whether the thread has stopped
     */
    public boolean shutdown(Duration timeout) {
        if (!stopping) {
            stopping = true;
            queue.add(STOP);
        }
        if (inExecutorThread()) {
            return false;
        }
        try {
            thread.join(timeout.toMillis());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        return !thread.isAlive();
    }

    private void run() {
        while (true) {
            Runnable task;
            try {
                task = queue.take();
            } catch (InterruptedException e) {
                return;
            }
            if (task == STOP) {
                return;
            }
            try {
                task.run();
            } catch (RuntimeException e) {
                LOG.error("Task failed on {}", thread.getName(), e);
            }
        }
    }
}
