package io.dtron.engine.internal.clock;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.Event;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

class RealClockTest {

    /**
     * The tester's race: it finds no output waiting and acts at the time now (an input: {@link RunClock#quietNow}),
     * or finds the time reached with no output waiting (a deadline: {@link RunClock#awaitUntil} returns null), while
     * adapter threads report. No output may then come in with an earlier time than that: with the time read apart
     * from the queueing, a reporter held up in between (descheduled, or waiting for the queue) delivered one.
     */
    @ParameterizedTest(name = "at a deadline: {0}")
    @ValueSource(booleans = {false, true})
    @Timeout(value = 60, unit = TimeUnit.SECONDS)
    void noOutputComesInWithATimeBeforeAQuietTimeTheTesterActedAt(boolean deadline) throws Exception {
        RealClock clock = new RealClock();
        clock.begin(java.util.OptionalLong.empty());
        int reporters = 3;
        int each = 100_000;
        List<Thread> threads = new ArrayList<>();
        for (int r = 0; r < reporters; r++) {
            Thread thread = new Thread(() -> {
                for (int i = 0; i < each; i++) {
                    clock.report(Event.of("tick"));
                    long pause = System.nanoTime() + 2_000; // leaves the queue empty now and then
                    while (System.nanoTime() < pause) {
                        Thread.onSpinWait();
                    }
                }
            });
            thread.start();
            threads.add(thread);
        }
        long quiet = -1;
        int received = 0;
        int before = 0;
        String first = null;
        while (received < reporters * each) {
            RunClock.TimedEvent output;
            if (deadline) {
                long until = clock.nowMicros();
                output = clock.awaitUntil(until);
                if (output == null) {
                    quiet = until;
                }
            } else {
                long now = clock.quietNow();
                if (now >= 0) {
                    quiet = now;
                }
                output = clock.drain();
            }
            if (output != null) {
                received++;
                if (output.micros() < quiet && before++ == 0) {
                    first = "output at " + output.micros() + " us after the tester acted at " + quiet + " us";
                }
            }
        }
        for (Thread thread : threads) {
            thread.join();
        }
        assertEquals(0, before, before + " outputs came in before a quiet time, the first: " + first);
        assertTrue(quiet >= 0, "the tester found the queue empty at least once");
    }

    @org.junit.jupiter.api.Test
    void itKeepsTheLatestItWokeUpAfterATargetAndVirtualTimeIsNeverLate() {
        RealClock clock = new RealClock();
        clock.begin(java.util.OptionalLong.empty());
        assertEquals(0, clock.worstLatenessMicros());
        long worst = 0;
        for (int i = 1; i <= 20; i++) {
            long target = clock.nowMicros() + 500;
            assertEquals(null, clock.awaitUntil(target));
            worst = Math.max(worst, clock.nowMicros() - target);
        }
        // the clock's own figure is taken right on waking, so it is at most what the caller sees afterwards (a
        // spun wait may well wake on the microsecond every time: zero is a fine figure)
        assertTrue(clock.worstLatenessMicros() >= 0, "lateness " + clock.worstLatenessMicros());
        assertTrue(clock.worstLatenessMicros() <= worst, clock.worstLatenessMicros() + " > " + worst);
        long before = clock.worstLatenessMicros();
        assertEquals(null, clock.awaitUntil(clock.nowMicros() - 10), "a target already past: no wait, no lateness");
        assertEquals(before, clock.worstLatenessMicros());
        VirtualClock virtual = new VirtualClock();
        virtual.awaitUntil(1_000_000);
        assertEquals(0, virtual.worstLatenessMicros());
    }

    /** A thread descheduled while it waits sees its time jump past the target: the clock keeps how far. */
    @org.junit.jupiter.api.Test
    void aWaitThatWakesUpPastItsTargetIsKeptAsLateness() {
        long jump = 3_000_000_000L; // 3 s, as a thread held up in its sleep sees it
        java.util.concurrent.atomic.AtomicLong armedAt = new java.util.concurrent.atomic.AtomicLong(-1);
        java.util.concurrent.atomic.AtomicInteger readsSinceArmed = new java.util.concurrent.atomic.AtomicInteger();
        RealClock clock = new RealClock(() -> {
            long armed = armedAt.get();
            if (armed < 0) {
                return System.nanoTime();
            }
            // the wait's first reading is the time it was armed at (5 ms before the target: the clock sleeps),
            // every later one is 3 s on
            return readsSinceArmed.getAndIncrement() == 0 ? armed : System.nanoTime() + jump;
        });
        clock.begin(java.util.OptionalLong.empty());
        long armed = System.nanoTime();
        long target = clock.nowMicros() + 5_000; // read after `armed`: the wait's first reading is 5 ms or more before it
        armedAt.set(armed);
        assertEquals(null, clock.awaitUntil(target));
        long seen = clock.nowMicros() - target;
        assertTrue(clock.worstLatenessMicros() >= 2_990_000, "lateness " + clock.worstLatenessMicros());
        assertTrue(clock.worstLatenessMicros() <= seen, clock.worstLatenessMicros() + " > " + seen);
    }

    @org.junit.jupiter.api.Test
    @Timeout(value = 60, unit = TimeUnit.SECONDS)
    void aLooseWaitReachesItsTimeOrAnOutputAndIsNotCountedAsLateness() throws Exception {
        RealClock clock = new RealClock();
        clock.begin(java.util.OptionalLong.empty());
        long target = clock.nowMicros() + 5_000;
        assertEquals(null, clock.awaitLooselyUntil(target));
        assertTrue(clock.nowMicros() >= target, "returned at " + clock.nowMicros() + ", before " + target);
        // however late it woke up, a loose wait is no measure of how late the tester acts
        assertEquals(0, clock.worstLatenessMicros());
        clock.report(Event.of("tick"));
        RunClock.TimedEvent output = clock.awaitLooselyUntil(clock.nowMicros() + 60_000_000);
        assertEquals(Event.of("tick"), output.event());
    }
}
