package io.dtron.cli;

import io.dtron.engine.Event;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import java.io.PrintWriter;
import java.time.Duration;
import java.util.Locale;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * A progress line every {@link #EVERY} of wall-clock time, whether or not anything happens, so that a long quiet
 * run does not look hung: the elapsed time, the test time, the inputs and outputs so far, and what the tester waits
 * for next (an input, the deadline of an output, or the end). Closing it stops the lines.
 */
final class Progress implements TestListener, AutoCloseable {
    static final Duration EVERY = Duration.ofSeconds(5);

    private final PrintWriter out;
    private final long unitMicros;
    private final boolean virtualTime;
    private final long startNanos = System.nanoTime();
    private final AtomicInteger inputs = new AtomicInteger();
    private final AtomicInteger outputs = new AtomicInteger();
    private final ScheduledExecutorService timer;
    private volatile Wait last;

    /** The tester's latest wait: its test time then, when that was on the wall clock, and what it waits for. */
    private record Wait(long nowMicros, long atNanos, long untilMicros, Until until) {
    }

    /** Starts the lines of a run with these options. */
    Progress(PrintWriter out, TestOptions options) {
        this.out = out;
        this.unitMicros = options.timeUnitMicros();
        this.virtualTime = options.virtualTime();
        timer = every(this::print);
    }

    /**
     * Runs {@code line} every {@link #EVERY} on a daemon thread of its own, the first time {@link #EVERY} from now;
     * {@link #stop} ends it.
     */
    static ScheduledExecutorService every(Runnable line) {
        ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(task -> {
            Thread thread = new Thread(task, "dtron-progress");
            thread.setDaemon(true);
            return thread;
        });
        timer.scheduleAtFixedRate(line, EVERY.toMillis(), EVERY.toMillis(), TimeUnit.MILLISECONDS);
        return timer;
    }

    /** Ends the lines of a timer {@link #every} made, waiting a second at most for a line being printed. */
    static void stop(ScheduledExecutorService timer) {
        timer.shutdownNow();
        try {
            timer.awaitTermination(1, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    @Override
    public void inputApplied(Event input, long micros) {
        inputs.incrementAndGet();
    }

    @Override
    public void outputObserved(Event output, long micros) {
        outputs.incrementAndGet();
    }

    @Override
    public void waiting(long nowMicros, long untilMicros, Until until) {
        last = new Wait(nowMicros, System.nanoTime(), untilMicros, until);
    }

    private void print() {
        long now = System.nanoTime();
        StringBuilder line = new StringBuilder(String.format(Locale.ROOT, "progress: %.0f s elapsed",
                (now - startNanos) / 1e9));
        Wait wait = last;
        if (wait != null) {
            // in real time the test time moves on with the wall clock while the tester waits
            long testMicros = virtualTime ? wait.nowMicros()
                    : Math.min(wait.untilMicros(), wait.nowMicros() + (now - wait.atNanos()) / 1000);
            line.append(", t=").append(units(testMicros));
        }
        line.append(", ").append(inputs.get()).append(" inputs, ").append(outputs.get()).append(" outputs");
        if (wait != null) {
            line.append(switch (wait.until()) {
                case INPUT -> ", next input at t=";
                case OUTPUT_DEADLINE -> ", an output is due by t=";
                case END -> ", the test ends at t=";
            }).append(units(wait.untilMicros()));
        }
        out.println(line);
        out.flush();
    }

    private String units(long micros) {
        return String.format(Locale.ROOT, "%.3f", micros / (double) unitMicros);
    }

    @Override
    public void close() {
        stop(timer);
    }
}
