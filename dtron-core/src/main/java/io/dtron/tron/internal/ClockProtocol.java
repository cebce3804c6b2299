package io.dtron.tron.internal;

import java.io.IOException;

/**
 * The command codes and result codes of TRON's virtual clock protocol: a command is one byte followed by its int32
 * arguments (big-endian); replies are int32.
 */
public final class ClockProtocol {
    /** The thread blocks outside the clock's knowledge and no longer holds time back; reply 0. */
    public static final int DEACTIVATE = 1;
    /** The thread takes part in virtual time again; reply 0. */
    public static final int ACTIVATE = 2;
    /** A new mutex; reply its id. */
    public static final int MUTEX_INIT = 3;
    /** {@code [4][id]}: destroys a mutex; no reply. */
    public static final int MUTEX_DESTROY = 4;
    /** {@code [5][id]}: locks a mutex; reply 0 once it is held. */
    public static final int MUTEX_LOCK = 5;
    /** {@code [6][id]}: unlocks a mutex; reply 0. */
    public static final int MUTEX_UNLOCK = 6;
    /** A new condition; reply its id. */
    public static final int CONDITION_INIT = 7;
    /** {@code [8][id]}: destroys a condition; no reply. */
    public static final int CONDITION_DESTROY = 8;
    /** {@code [9][condition][mutex]}: waits until signalled; reply 0 with the mutex held again. */
    public static final int WAIT = 9;
    /** {@code [10][condition][mutex][s][us]}: waits until an absolute virtual time; reply 0 or {@link #TIMED_OUT}. */
    public static final int TIMED_WAIT = 10;
    /** {@code [11][condition][mutex][s][us]}: waits at most that long from now; reply 0 or {@link #TIMED_OUT}. */
    public static final int DELAY = 11;
    /** {@code [12][condition]}: wakes one waiter; reply 0. */
    public static final int SIGNAL = 12;
    /** {@code [13][condition]}: wakes every waiter; no reply. */
    public static final int BROADCAST = 13;
    /** The virtual time; reply two int32, seconds and microseconds. */
    public static final int GET_TIME = 14;
    /** The thread ends; no reply. */
    public static final int QUIT = 127;

    /** Result: done. */
    public static final int OK = 0;
    /** Result: refused (a mutex the thread does not hold). */
    public static final int ERROR = 64;
    /** Result: a timed wait reached its time. */
    public static final int TIMED_OUT = 65;

    private ClockProtocol() {
    }

    /** A command the server cannot take: unknown, or naming a mutex or condition that does not exist. */
    public static final class Malformed extends IOException {
        private static final long serialVersionUID = 1L;

        /** A malformed command, with why. */
        public Malformed(String message) {
            super(message);
        }
    }
}
