package com.uppaal.tron;

import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;

/**
 * A mutex with a condition that works in virtual time (through the clock server, by the virtual thread that uses
 * it) or in real time (a plain lock). Not reentrant.
 */
public final class VirtualLock {
    private final ReentrantLock real = new ReentrantLock();
    private final Condition realCondition = real.newCondition();
    private int mutex;
    private int condition;

    private synchronized int[] ids() {
        if (mutex == 0) {
            VirtualThread t = VirtualThread.current();
            mutex = t.call(3, 1)[0];
            condition = t.call(7, 1)[0];
        }
        return new int[] {mutex, condition};
    }

    /** Takes the lock. */
    public void lock() {
        if (VirtualThread.isVirtual()) {
            VirtualThread.current().call(5, 1, ids()[0]);
        } else {
            real.lock();
        }
    }

    /** Releases the lock. */
    public void unlock() {
        if (VirtualThread.isVirtual()) {
            VirtualThread.current().call(6, 1, ids()[0]);
        } else {
            real.unlock();
        }
    }

    /** With the lock held: waits until signalled. */
    public void await() throws InterruptedException {
        if (VirtualThread.isVirtual()) {
            int[] ids = ids();
            VirtualThread.current().call(9, 1, ids[1], ids[0]);
        } else {
            realCondition.await();
        }
    }

    /**
     * With the lock held: waits until signalled or until time {@code micros} (of {@link VirtualThread#getTimeMicros});
     * returns false when the time came.
     */
    public boolean awaitUntil(long micros) throws InterruptedException {
        if (VirtualThread.isVirtual()) {
            int[] ids = ids();
            int code = VirtualThread.current().call(10, 1, ids[1], ids[0], (int) (micros / 1_000_000),
                    (int) (micros % 1_000_000))[0];
            return code != 65;
        }
        long left = micros - VirtualThread.getTimeMicros();
        return left > 0 && realCondition.await(left, TimeUnit.MICROSECONDS);
    }

    /** Wakes every waiter. */
    public void signalAll() {
        if (VirtualThread.isVirtual()) {
            int[] ids = ids();
            VirtualThread.current().call(13, 0, ids[1]);
        } else {
            realCondition.signalAll();
        }
    }
}
