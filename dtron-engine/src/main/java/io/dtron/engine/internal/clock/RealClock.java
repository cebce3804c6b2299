package io.dtron.engine.internal.clock;

/** Real time: microseconds of {@link System#nanoTime()} since the start of the run. */
public final class RealClock extends RunClock {
    private volatile long start = System.nanoTime();
    private volatile long worstLateness;

    @Override
    public void begin(java.util.OptionalLong zeroNanoTime) {
        if (zeroNanoTime.isEmpty()) {
            start = System.nanoTime();
            return;
        }
        long zero = zeroNanoTime.getAsLong();
        long ahead;
        while ((ahead = zero - System.nanoTime()) > 0) {
            try {
                java.util.concurrent.TimeUnit.NANOSECONDS.sleep(ahead);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                break;
            }
        }
        start = zero;
    }

    @Override
    public long nowMicros() {
        return (System.nanoTime() - start) / 1000;
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
                if (slept && -remaining > worstLateness) {
                    worstLateness = -remaining;
                }
                return true;
            }
            slept = true;
            try {
                awaitOutput(remaining * 1000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return true;
            }
        }
    }
}
