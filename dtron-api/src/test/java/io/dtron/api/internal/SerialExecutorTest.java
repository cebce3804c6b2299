package io.dtron.api.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.Waits;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import org.junit.jupiter.api.Test;

class SerialExecutorTest {
    private final SerialExecutor executor = new SerialExecutor("serial-executor-test");

    @Test
    void awaitQueuedReturnsOnceTheTasksQueuedBeforeHaveRun() throws Exception {
        CountDownLatch release = new CountDownLatch(1);
        AtomicBoolean ran = new AtomicBoolean();
        executor.execute(() -> {
            try {
                release.await();
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            ran.set(true);
        });
        // the task before it holds the thread: not run yet, whatever the wait
        assertFalse(executor.awaitQueued(Duration.ofMillis(50)));
        release.countDown();
        assertTrue(executor.awaitQueued(Waits.TIMEOUT));
        assertTrue(ran.get());
        assertTrue(executor.shutdown(Waits.TIMEOUT));
    }

    @Test
    void onItsOwnThreadItReturnsAtOnceAndAfterShutdownToo() throws Exception {
        CompletableFuture<Boolean> inTask = new CompletableFuture<>();
        CountDownLatch hold = new CountDownLatch(1);
        executor.execute(() -> {
            try {
                inTask.complete(executor.awaitQueued(Waits.TIMEOUT));
                hold.await();
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        });
        assertEquals(true, inTask.get(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS), "no wait for itself");
        hold.countDown();
        assertTrue(executor.shutdown(Waits.TIMEOUT));
        // a task queued now never runs: it says so without waiting for the timeout
        long start = System.nanoTime();
        assertFalse(executor.awaitQueued(Waits.TIMEOUT));
        assertTrue(System.nanoTime() - start < Waits.TIMEOUT.toNanos(), "it did not wait out the timeout");
    }
}
