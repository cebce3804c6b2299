package io.dtron.tron;

/**
 * A small smart lamp for TRON's {@code LightContr.xml} (the IUT part of that model, run deterministically): inputs
 * grasp and release reach the lamp 1 unit after they are applied; a grasp released from 20 units on and before 50
 * is a touch that switches the light; a grasp held 50 units is a hold that dims the level one step every 100 units;
 * each level is reported 1 unit after it is set. The faulty variant reports every level 20 units after setting it,
 * where the model allows 5.
 */
final class TestLamp {
    private static final int EPSILON = 20;
    private static final int DELTA = 50;
    private static final int DELAY = 100;
    private static final int MAX = 10;
    private static final int LATENCY = 1;
    private static final int LATE = 20;

    /** What the lamp needs from its adapter: a clock with timers, and a way to report the level. */
    interface Io {
        long nowMicros();

        Cancel schedule(long micros, Runnable task);

        void level(int value);
    }

    /** A timer. */
    interface Cancel {
        void cancel();
    }

    private enum Hand { IDLE, GRASPED, HOLDING }

    private final Io io;
    private final long unit;
    private final int reportLatency;
    private Hand hand = Hand.IDLE;
    private long graspedAt;
    private Cancel holdStart;
    private Cancel nextStep;
    private boolean dimmingUp;
    private boolean lastHoldUp;
    private boolean on;
    private int level;
    private int oldLevel;

    TestLamp(Io io, long unitMicros, boolean late) {
        this.io = io;
        this.unit = unitMicros;
        this.reportLatency = late ? LATE : LATENCY;
    }

    void grasp() {
        later(LATENCY, () -> {
            if (hand == Hand.IDLE) {
                hand = Hand.GRASPED;
                graspedAt = io.nowMicros();
                holdStart = later(DELTA, this::startHold);
            }
        });
    }

    void release() {
        later(LATENCY, () -> {
            if (hand == Hand.GRASPED) {
                holdStart.cancel();
                hand = Hand.IDLE;
                if (io.nowMicros() - graspedAt >= EPSILON * unit) {
                    touch();
                }
            } else if (hand == Hand.HOLDING) {
                hand = Hand.IDLE;
                nextStep.cancel();
                lastHoldUp = dimmingUp;
            }
        });
    }

    private void touch() {
        if (on) {
            oldLevel = level;
            level = 0;
        } else {
            level = oldLevel;
        }
        on = !on;
        setLevel();
    }

    private void startHold() {
        hand = Hand.HOLDING;
        on = true;
        if (!lastHoldUp) {
            level = oldLevel;
            dimmingUp = true;
            setLevel();
        } else {
            oldLevel = level;
            dimmingUp = false;
        }
        nextStep = later(DELAY, this::step);
    }

    private void step() {
        if (dimmingUp && level == MAX) {
            dimmingUp = false;
        } else if (!dimmingUp && level == 0) {
            dimmingUp = true;
        }
        level += dimmingUp ? 1 : -1;
        setLevel();
        nextStep = later(DELAY, this::step);
    }

    private void setLevel() {
        int value = level;
        later(reportLatency, () -> io.level(value));
    }

    private Cancel later(int units, Runnable task) {
        return io.schedule(units * unit, task);
    }
}
