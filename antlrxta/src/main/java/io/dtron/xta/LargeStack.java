package io.dtron.xta;

/**
 * Runs work on a thread with a {@value #MEGABYTES} MB stack and waits for it. Parsing, building and checking
 * a model recurse once per level of nesting; a thread's default stack of 1 MB holds an expression nested to
 * the front end's limit of 1,000 levels only just, and not the deepest nesting of every kind at once. Work
 * that is already on such a thread runs directly.
 *
 * <p>What the work throws is thrown in the caller's thread, after the work's thread has ended: what the work
 * had built is garbage by then, so that a caller that catches an {@link OutOfMemoryError} has memory again.
 */
public final class LargeStack {
    /** The stack size of the threads, in MB. */
    public static final int MEGABYTES = 32;

    private LargeStack() {
    }

    /**
     * Work that returns a value or throws {@code E}.
     *
     * @param <T> the value
     * @param <E> the checked exception it may throw
     */
    @FunctionalInterface
    public interface Work<T, E extends Exception> {
        /** Does the work. */
        T run() throws E;
    }

    private static final class LargeStackThread extends Thread {
        LargeStackThread(Runnable body) {
            super(null, body, "dtron-large-stack", (long) MEGABYTES << 20);
            setDaemon(true);
        }
    }

    /**
     * Runs {@code work} on a thread with a large stack and returns its value, or throws what it threw. Waits
     * uninterruptibly (the work holds nothing the caller could release) and keeps the caller's interrupt.
     */
    @SuppressWarnings("unchecked")
    public static <T, E extends Exception> T call(Work<T, E> work) throws E {
        if (Thread.currentThread() instanceof LargeStackThread) {
            return work.run();
        }
        Object[] outcome = new Object[1];
        boolean[] threw = new boolean[1];
        Thread thread = new LargeStackThread(() -> {
            try {
                outcome[0] = work.run();
            } catch (Exception | Error e) {
                // kept without allocating: the heap may be full
                outcome[0] = e;
                threw[0] = true;
            }
        });
        thread.start();
        boolean interrupted = false;
        while (thread.isAlive()) {
            try {
                thread.join();
            } catch (InterruptedException e) {
                interrupted = true;
            }
        }
        if (interrupted) {
            Thread.currentThread().interrupt();
        }
        if (threw[0]) {
            if (outcome[0] instanceof Error error) {
                throw error;
            } else if (outcome[0] instanceof RuntimeException runtime) {
                throw runtime;
            }
            throw (E) outcome[0];
        }
        return (T) outcome[0];
    }
}
