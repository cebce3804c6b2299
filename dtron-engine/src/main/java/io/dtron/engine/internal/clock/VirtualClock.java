package io.dtron.engine.internal.clock;

/**
 * Virtual time: it jumps to the next scheduled task or the tester's next deadline, so a run takes as long as
 * its computations and is the same every time for the same seed.
 */
public final class VirtualClock extends RunClock {
    private volatile long now;

    @Override
    public long nowMicros() {
        return now;
    }

    @Override
    protected boolean waitFor(long targetMicros) {
        if (hasOutput()) {
            return false;
        }
        if (targetMicros > now) {
            now = targetMicros;
        }
        return true;
    }
}
