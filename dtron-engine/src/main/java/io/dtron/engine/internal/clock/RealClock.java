package io.dtron.engine.internal.clock;

/**
 * Real time: microseconds of {@link System#nanoTime()} since the start of the run. A wait sleeps until {@value
 * #SPIN_MICROS} us before its target and spins the rest, so that the tester acts on time even where a timed sleep
 * wakes up late.
 */
public final class RealClock extends RunClock {
    /** How long before a target the clock stops sleeping and spins, in microseconds. */
    private static final long SPIN_MICROS = 1000;
    private final java.util.function.LongSupplier nanoTime;
    private volatile long start;
    private volatile long worstLateness;

    /** A clock of {@link System#nanoTime()}. */
    public RealClock() {
        this(System::nanoTime);
    }

    /** A clock of the given nanosecond source (tests make it jump, as a descheduled thread sees it). */
    RealClock(java.util.function.LongSupplier nanoTime) {
        this.nanoTime = nanoTime;
        this.start = nanoTime.getAsLong();
    }

    @Override
    public void begin(java.util.OptionalLong zeroNanoTime) {
        if (zeroNanoTime.isEmpty()) {
            start = nanoTime.getAsLong();
            return;
        }
        long zero = zeroNanoTime.getAsLong();
        long ahead;
        while ((ahead = zero - nanoTime.getAsLong()) > SPIN_MICROS * 1000) {
            try {
                java.util.concurrent.TimeUnit.NANOSECONDS.sleep(ahead - SPIN_MICROS * 1000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                break;
            }
        }
        while (nanoTime.getAsLong() < zero && !Thread.currentThread().isInterrupted()) {
            Thread.onSpinWait();
        }
        start = zero;
    }

    @Override
    public long nowMicros() {
        return (nanoTime.getAsLong() - start) / 1000;
    }

    @Override
    public long worstLatenessMicros() {
        return worstLateness;
    }

    @Override
    protected boolean waitFor(long targetMicros) {
        boolean slept = false;
        while (true) {
            if (hasOutput()) {
                return false;
            }
            long remaining = targetMicros - nowMicros();
            if (remaining <= 0) {
                if (slept && !loose() && -remaining > worstLateness) {
                    worstLateness = -remaining;
                }
                return true;
            }
            slept = true;
            if (loose()) {
                try {
                    awaitOutput(remaining * 1000);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    return true;
                }
                continue;
            }
            if (remaining <= SPIN_MICROS) {
                // a timed wait may end milliseconds late on an idle CPU (of a virtual machine above all): the last
                // stretch before the target is spun, watching for outputs
                while (!hasOutput() && nowMicros() < targetMicros) {
                    Thread.onSpinWait();
                }
                continue;
            }
            try {
                awaitOutput((remaining - SPIN_MICROS) * 1000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return true;
            }
        }
    }
}
