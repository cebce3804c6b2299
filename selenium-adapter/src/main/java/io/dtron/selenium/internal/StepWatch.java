package io.dtron.selenium.internal;

import java.util.Map;
import java.util.Objects;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.function.Consumer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. Watches the steps the users' threads run: a step that takes longer than the slow-step threshold is
 * logged while it is still running, with what its thread is doing then (the WebDriver call it waits for, and the
 * adapter's line that made it, taken from the thread's stack), so that a step blocked in the browser shows in the
 * log before the tester's verdict and not only after it.
 */
public final class StepWatch implements AutoCloseable {
    private static final Logger LOG = LoggerFactory.getLogger(StepWatch.class);
    private static final String SELENIUM = "org.openqa.selenium.";

    private final long slowNanos;
    private final long timeoutNanos;
    private final Consumer<String> timedOut;
    private final Map<Integer, Step> running = new ConcurrentHashMap<>();
    private final ScheduledExecutorService timer;

    /**
     * A watch that logs steps running longer than {@code slowMillis}, and gives up on a step that runs longer
     * than {@code timeoutMillis}.
     *
     * @param slowMillis    the threshold of the log, positive
     * @param timeoutMillis the bound of a step, at least {@code slowMillis}
     * @param timedOut      called once, with a description of the step and of what it waits for, when a step
     *                      outlives the bound
     */
    public StepWatch(long slowMillis, long timeoutMillis, Consumer<String> timedOut) {
        if (slowMillis <= 0 || timeoutMillis < slowMillis) {
            throw new IllegalArgumentException("need 0 < slow-step threshold <= step timeout: " + slowMillis
                    + ", " + timeoutMillis);
        }
        this.slowNanos = TimeUnit.MILLISECONDS.toNanos(slowMillis);
        this.timeoutNanos = TimeUnit.MILLISECONDS.toNanos(timeoutMillis);
        this.timedOut = Objects.requireNonNull(timedOut, "timedOut");
        this.timer = Executors.newSingleThreadScheduledExecutor(r -> {
            Thread t = new Thread(r, "selenium-step-watch");
            t.setDaemon(true);
            return t;
        });
        long period = Math.max(50, Math.min(500, slowMillis / 4));
        timer.scheduleWithFixedDelay(this::check, period, period, TimeUnit.MILLISECONDS);
    }

    /** Returns the slow-step threshold in milliseconds. */
    public long slowMillis() {
        return TimeUnit.NANOSECONDS.toMillis(slowNanos);
    }

    /** One step under way on a user's thread. */
    public static final class Step {
        private final int user;
        private final String what;
        private final Class<?> adapter;
        private final Thread thread;
        private final long queuedNanos;
        private final long startNanos;
        private volatile long browserStartNanos;
        private volatile long reportNanos;
        private volatile boolean loggedSlow;
        private volatile boolean timedOut;

        private Step(int user, String what, Class<?> adapter, Thread thread, long queuedNanos, long startNanos) {
            this.user = user;
            this.what = what;
            this.adapter = adapter;
            this.thread = thread;
            this.queuedNanos = queuedNanos;
            this.startNanos = startNanos;
        }

        /** Returns how long the step waited for its user's thread before it started, in milliseconds. */
        public long queuedMillis() {
            return TimeUnit.NANOSECONDS.toMillis(startNanos - queuedNanos);
        }

        /** Returns how long the step has run (or ran, until its result), in milliseconds. */
        public long millis() {
            long end = reportNanos;
            return TimeUnit.NANOSECONDS.toMillis((end != 0 ? end : System.nanoTime()) - startNanos);
        }

        /** Returns how long the step spent starting its user's browser, in milliseconds (0 if it did not). */
        public long browserStartMillis() {
            return TimeUnit.NANOSECONDS.toMillis(browserStartNanos);
        }

        /** Notes that the step spent this long starting its user's browser. */
        public void browserStarted(long nanos) {
            browserStartNanos += nanos;
        }

        /** Notes that the step's result was reported now: the step's time ends here. */
        public void reported() {
            if (reportNanos == 0) {
                reportNanos = System.nanoTime();
            }
        }

        /**
         * Returns the times of the step for a log line: {@code 716 ms (waited 0 ms for the user's thread)},
         * with the time spent starting the browser if it did.
         */
        public String timing() {
            long browser = browserStartMillis();
            return millis() + " ms (waited " + queuedMillis() + " ms for the user's thread"
                    + (browser > 0 ? "; " + browser + " ms of it starting the browser" : "") + ")";
        }
    }

    /**
     * Notes that a step starts on the current thread.
     *
     * @param user        the step's user
     * @param what        the adapter and the message, for the log
     * @param adapter     the adapter's class, whose lines the log names
     * @param queuedNanos when the message was queued on the user's thread ({@link System#nanoTime()})
     */
    public Step begin(int user, String what, Class<?> adapter, long queuedNanos) {
        Step step = new Step(user, Objects.requireNonNull(what, "what"), adapter, Thread.currentThread(),
                queuedNanos, System.nanoTime());
        running.put(user, step);
        return step;
    }

    /** Returns the step under way on the current thread, or null if there is none. */
    public Step current(int user) {
        Step step = running.get(user);
        return step != null && step.thread == Thread.currentThread() ? step : null;
    }

    /** Notes that a step ended. */
    public void end(Step step) {
        running.remove(step.user, step);
    }

    /**
     * Returns what the thread of a step is doing now, from its stack: starting the browser, or the outermost
     * WebDriver call with the line that made it and the adapter's line under way.
     */
    public static String doing(Thread thread, Class<?> adapter) {
        return doing(thread.getStackTrace(), adapter.getName());
    }

    static String doing(StackTraceElement[] stack, String adapter) {
        StackTraceElement own = null;
        for (StackTraceElement frame : stack) {
            if (frame.getClassName().equals("io.dtron.selenium.HeadlessChrome") && frame.getMethodName().equals(
                    "create")) {
                return "starting its browser (HeadlessChrome.create)";
            }
            if (own == null && (frame.getClassName().equals(adapter) || frame.getClassName().startsWith(adapter
                    + "$"))) {
                own = frame;
            }
        }
        String at = own == null ? "" : " at " + line(own);
        for (int i = stack.length - 1; i >= 0; i--) {
            if (stack[i].getClassName().startsWith(SELENIUM)) {
                StackTraceElement call = stack[i];
                StackTraceElement caller = i + 1 < stack.length ? stack[i + 1] : null;
                return "waiting in the WebDriver call " + simpleName(call.getClassName()) + "." + call.getMethodName()
                        + (caller == null || caller.equals(own) ? "" : " made in " + simpleName(caller.getClassName())
                        + "." + caller.getMethodName()) + at + " (innermost frame " + simpleName(stack[0]
                        .getClassName()) + "." + stack[0].getMethodName() + ")";
            }
        }
        return own == null ? "not in the adapter's code" : "running" + at;
    }

    /** A frame as {@code com.example.web.Greet.execute(Greet.java:24)}, without the class loader's name. */
    private static String line(StackTraceElement frame) {
        return frame.getClassName() + "." + frame.getMethodName() + "(" + frame.getFileName() + ":"
                + frame.getLineNumber() + ")";
    }

    private static String simpleName(String type) {
        return type.substring(type.lastIndexOf('.') + 1);
    }

    private void check() {
        long now = System.nanoTime();
        for (Step step : running.values()) {
            if (step.reportNanos != 0) {
                continue;
            }
            long ran = now - step.startNanos;
            if (!step.timedOut && ran > timeoutNanos) {
                step.timedOut = true;
                step.loggedSlow = true;
                timedOut.accept(step.what + " for user " + step.user + " has run " + TimeUnit.NANOSECONDS.toMillis(
                        ran) + " ms, more than the step timeout of " + TimeUnit.NANOSECONDS.toMillis(timeoutNanos)
                        + " ms: " + doing(step.thread, step.adapter));
            } else if (!step.loggedSlow && ran > slowNanos) {
                step.loggedSlow = true;
                LOG.warn("{} for user {} is still running after {} ms (waited {} ms for the user's thread{}): {}",
                        step.what, step.user, TimeUnit.NANOSECONDS.toMillis(ran), step.queuedMillis(),
                        step.browserStartNanos > 0 ? "; started the browser in " + step.browserStartMillis() + " ms"
                                : "", doing(step.thread, step.adapter));
            }
        }
    }

    /** Stops watching. */
    @Override
    public void close() {
        timer.shutdownNow();
    }
}
