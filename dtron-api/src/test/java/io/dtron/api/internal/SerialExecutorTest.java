package io.dtron.api.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.Waits;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
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

    @Test
    void anIdleExecutorRunsTheTaskOnTheCallersThreadAndABusyOneQueuesIt() throws Exception {
        CompletableFuture<Thread> ranOn = new CompletableFuture<>();
        assertTrue(executor.runOrExecute(() -> ranOn.complete(Thread.currentThread())));
        assertEquals(Thread.currentThread(), ranOn.get(), "run inline");

        List<String> order = new CopyOnWriteArrayList<>();
        CountDownLatch release = new CountDownLatch(1);
        CountDownLatch holding = new CountDownLatch(1);
        // a task that blocks inline on another thread holds the executor: a task submitted meanwhile waits behind it
        Thread blocker = new Thread(() -> executor.runOrExecute(() -> {
            holding.countDown();
            await(release);
            order.add("blocking");
        }));
        blocker.start();
        assertTrue(holding.await(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS));
        assertFalse(executor.inExecutorThread());
        assertFalse(executor.runOrExecute(() -> order.add("queued")), "queued, not run beside the blocking one");
        assertFalse(executor.awaitQueued(Duration.ofMillis(20)), "not run while the blocking task runs");
        assertEquals(List.of(), order);
        release.countDown();
        assertTrue(executor.awaitQueued(Waits.TIMEOUT));
        assertEquals(List.of("blocking", "queued"), order);
        blocker.join();
        assertTrue(executor.shutdown(Waits.TIMEOUT));
    }

    @Test
    void aTaskSubmittedFromAnInlineTaskRunsAfterItAndItsContinuationBeforeAnyQueuedMeanwhile() throws Exception {
        List<String> order = new CopyOnWriteArrayList<>();
        AtomicBoolean nestedRanInline = new AtomicBoolean(true);
        assertTrue(executor.runOrExecute(() -> {
            assertTrue(executor.inExecutorThread());
            executor.execute(() -> order.add("queued meanwhile"));
            nestedRanInline.set(executor.runOrExecute(() -> order.add("submitted from the task")));
            executor.continueOnOwnThread(() -> order.add("continuation"));
            order.add("inline");
        }));
        assertFalse(nestedRanInline.get(), "never nested in the running task");
        assertTrue(executor.awaitQueued(Waits.TIMEOUT));
        assertEquals(List.of("inline", "continuation", "queued meanwhile", "submitted from the task"), order);
        assertFalse(executor.runsInline());
        assertThrows(IllegalStateException.class, () -> executor.continueOnOwnThread(() -> { }));
        assertTrue(executor.shutdown(Waits.TIMEOUT));
    }

    @Test
    void tasksFromSeveralThreadsRunOneAtATimeInTheOrderTheyWereSubmitted() throws Exception {
        // like a transport: several threads hand over messages, one at a time in the bus's order, some of them slow
        int threads = 4;
        int perThread = 500;
        Object bus = new Object();
        AtomicInteger next = new AtomicInteger();
        AtomicInteger running = new AtomicInteger();
        AtomicInteger mostAtOnce = new AtomicInteger();
        List<Integer> seen = new CopyOnWriteArrayList<>();
        List<Thread> senders = new ArrayList<>();
        for (int t = 0; t < threads; t++) {
            Thread sender = new Thread(() -> {
                for (int i = 0; i < perThread; i++) {
                    synchronized (bus) {
                        int number = next.getAndIncrement();
                        Runnable task = () -> {
                            mostAtOnce.accumulateAndGet(running.incrementAndGet(), Math::max);
                            if (number % 50 == 0) {
                                Thread.yield(); // a slower listener now and then: the next ones queue
                            }
                            seen.add(number);
                            running.decrementAndGet();
                        };
                        if (number % 3 == 0) {
                            executor.execute(task);
                        } else {
                            executor.runOrExecute(task);
                        }
                    }
                }
            });
            senders.add(sender);
            sender.start();
        }
        for (Thread sender : senders) {
            sender.join();
        }
        assertTrue(executor.awaitQueued(Waits.TIMEOUT));
        List<Integer> expected = new ArrayList<>();
        for (int i = 0; i < threads * perThread; i++) {
            expected.add(i);
        }
        assertEquals(expected, seen);
        assertEquals(1, mostAtOnce.get(), "one task at a time");
        assertTrue(executor.shutdown(Waits.TIMEOUT));
    }

    @Test
    void shutdownWaitsForAnInlineTaskAndRunsItsContinuation() throws Exception {
        CountDownLatch holding = new CountDownLatch(1);
        CountDownLatch release = new CountDownLatch(1);
        AtomicBoolean continued = new AtomicBoolean();
        Thread inline = new Thread(() -> executor.runOrExecute(() -> {
            holding.countDown();
            await(release);
            executor.continueOnOwnThread(() -> continued.set(true));
        }));
        inline.start();
        assertTrue(holding.await(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS));
        CompletableFuture<Boolean> stopped = CompletableFuture.supplyAsync(() -> executor.shutdown(Waits.TIMEOUT));
        release.countDown();
        assertTrue(stopped.get(Waits.TIMEOUT.toSeconds() * 2, TimeUnit.SECONDS));
        assertTrue(continued.get(), "the continuation ran before the thread stopped");
        inline.join();
    }

    private static void await(CountDownLatch latch) {
        try {
            latch.await();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
