package io.dtron.engine.internal.clock;

/** Real time: microseconds of {@link System#nanoTime()} since the start of the run. */
public final class RealClock extends RunClock {
    private volatile long start = System.nanoTime();

    @Override
    public void begin() {
        start = System.nanoTime();
    }

    @Override
    public long nowMicros() {
        return (System.nanoTime() - start) / 1000;
    }

    @Override
    protected boolean waitFor(long targetMicros) {
        while (true) {
            if (hasOutput()) {
                return false;
            }
            long remaining = targetMicros - nowMicros();
            if (remaining <= 0) {
                return true;
            }
            try {
                awaitOutput(remaining * 1000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return true;
            }
        }
    }
}
