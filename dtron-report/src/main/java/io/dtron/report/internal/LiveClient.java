package io.dtron.report.internal;

import java.io.IOException;
import java.io.OutputStream;
import java.nio.charset.StandardCharsets;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * One browser following the live view: a bounded queue of updates that the run's thread fills without waiting,
 * and the server thread that writes them to the browser as server-sent events. When the browser does not keep up
 * and the queue is full, the queued updates are dropped and the browser is told to fetch the whole state again
 * ({@code event: missed}): the browser loses updates, the run loses nothing.
 */
public final class LiveClient {
    /** How many updates a browser may be behind before it loses them. */
    public static final int QUEUE = 4096;
    private static final String MISSED = "\u0000missed";
    private static final String END = "\u0000end";
    private static final long KEEP_ALIVE_SECONDS = 10;

    private final BlockingQueue<String> queue;
    private final AtomicLong dropped = new AtomicLong();

    /** A browser that may be {@code size} updates behind. */
    public LiveClient(int size) {
        queue = new ArrayBlockingQueue<>(size);
    }

    /** Queues {@code update} for the browser; never waits. Called by the run's thread. */
    public void offer(String update) {
        if (!queue.offer(update)) {
            int lost = queue.size();
            queue.clear();
            dropped.addAndGet(lost + 1L);
            queue.offer(MISSED);
        }
    }

    /** Ends the stream after what is queued. */
    public void end() {
        if (!queue.offer(END)) {
            queue.clear();
            queue.offer(END);
        }
    }

    /** How many updates this browser lost because it did not read them in time. */
    public long dropped() {
        return dropped.get();
    }

    /**
     * Writes the queued updates to {@code out} until {@link #end} or until the browser goes away.
     *
     * @throws IOException when the browser has gone
     */
    public void stream(OutputStream out) throws IOException, InterruptedException {
        out.write(": dtron live view\n\n".getBytes(StandardCharsets.UTF_8));
        out.flush();
        while (true) {
            String update = queue.poll(KEEP_ALIVE_SECONDS, TimeUnit.SECONDS);
            String text;
            if (update == null) {
                text = ": keep-alive\n\n";
            } else if (update.equals(END)) {
                out.write("event: end\ndata: {}\n\n".getBytes(StandardCharsets.UTF_8));
                out.flush();
                return;
            } else if (update.equals(MISSED)) {
                text = "event: missed\ndata: {}\n\n";
            } else {
                text = "data: " + update + "\n\n";
            }
            out.write(text.getBytes(StandardCharsets.UTF_8));
            if (queue.isEmpty()) {
                out.flush();
            }
        }
    }
}
