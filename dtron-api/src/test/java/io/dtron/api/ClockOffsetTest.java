package io.dtron.api;

import io.dtron.api.internal.TestHooks;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.bus.internal.EpochClock;
import io.dtron.testadapter.ClockMemberMain;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.Waits;
import java.nio.file.Path;
import java.time.Duration;
import java.util.HashMap;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Members whose clocks are shifted against the tester's estimate the shift by pinging the tester, within the error
 * bound they give, in one JVM and in JVMs of their own; the run clock then fires at the tester's time.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class ClockOffsetTest {
    private static final long SHIFT_MILLIS = 50;

    /** The true offset of a member whose clock is shifted by {@code shift}, against an unshifted tester. */
    private static void assertWithinBound(long shiftNanos, long offsetNanos, long errorNanos, String who) {
        assertTrue(errorNanos > 0, who + ": an estimate has an error bound");
        assertTrue(Math.abs(offsetNanos + shiftNanos) <= errorNanos, who + ": offset " + offsetNanos
                + " ns is not within " + errorNanos + " ns of " + -shiftNanos + " ns");
    }

    static void awaitOffset(Dtron member) {
        Waits.await(member + "'s clock offset estimate").until(member::hasClockOffset);
    }

    @Test
    void membersInOneJvmEstimateTheirShiftWithinTheBound() throws Exception {
        String cluster = TestClusters.uniqueName("offset");
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
                Dtron ahead = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("ahead"),
                        Duration.ofMillis(SHIFT_MILLIS)).build());
                Dtron behind = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("behind"),
                        Duration.ofMillis(-SHIFT_MILLIS)).build())) {
            awaitOffset(ahead);
            awaitOffset(behind);
            assertEquals(Optional.of("tester"), ahead.getTester());
            assertEquals(Optional.of("tester"), behind.getTester());
            assertTrue(tester.hasClockOffset(), "the tester's own offset is exact");
            assertEquals(0, tester.getClockOffsetNanos());
            assertEquals(0, tester.getClockErrorNanos());
            assertEquals(Optional.of("tester"), tester.getTester());
            assertEquals(Optional.of(new ClockOffset("tester", 0, 0)), tester.getClockOffset());
            // every estimate, while they come, is within its bound
            long until = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(1_500);
            while (System.nanoTime() < until) {
                ClockOffset aheadOffset = ahead.getClockOffset().orElseThrow();
                ClockOffset behindOffset = behind.getClockOffset().orElseThrow();
                assertEquals("tester", aheadOffset.tester());
                assertWithinBound(TimeUnit.MILLISECONDS.toNanos(SHIFT_MILLIS), aheadOffset.offsetNanos(),
                        aheadOffset.errorNanos(), "ahead");
                assertWithinBound(-TimeUnit.MILLISECONDS.toNanos(SHIFT_MILLIS), behindOffset.offsetNanos(),
                        behindOffset.errorNanos(), "behind");
                // the tester's clock is the test's: its reading lies between the test's readings before and after,
                // give or take the estimate's error (a preemption between the reads widens the window, never breaks it)
                long before = EpochClock.nowNanos();
                long own = ahead.currentTimeNanos();
                long after = EpochClock.nowNanos();
                long onTesters = aheadOffset.toTesterNanos(own);
                assertTrue(onTesters >= before - aheadOffset.errorNanos() - 1_000_000
                        && onTesters <= after + aheadOffset.errorNanos() + 1_000_000,
                        onTesters + " not within [" + before + ", " + after + "] +/- " + aheadOffset.errorNanos());
                Thread.sleep(50);
            }
            assertEquals(0, tester.getStats().getPublished(), "hellos and pongs are not counted");
            assertEquals(0, ahead.getStats().getPublished(), "pings are not counted");
        }
    }

    @Test
    void aMemberForgetsTheTesterThatLeft() throws Exception {
        String cluster = TestClusters.uniqueName("offsetLeft");
        try (Dtron member = Dtron.connect(TestClusters.inJvm(cluster).memberName("member").build())) {
            assertFalse(member.hasClockOffset(), "no tester, no estimate");
            assertEquals(Optional.empty(), member.getTester());
            try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true)
                    .build())) {
                awaitOffset(member);
            }
            Waits.await("the estimate forgotten once its tester left").until(() -> !member.hasClockOffset());
            assertEquals(Optional.empty(), member.getTester());
            assertEquals(Optional.empty(), member.getClockOffset());
            assertEquals(0, member.getClockErrorNanos());
        }
    }

    @Test
    void membersInTheirOwnJvmsEstimateTheirShiftAndFireAtTheTestersTime(@TempDir Path dir) throws Exception {
        String cluster = TestClusters.uniqueName("offsetJvm");
        long unitMicros = 100_000;
        long fireAtNanos = (long) (ClockMemberMain.FIRE_AT_UNITS * unitMicros * 1_000);
        int port = FreePorts.range(FreePorts.BUS_RANGE);
        try (Dtron tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("tester")
                .port(port).portRange(FreePorts.BUS_RANGE).tester(true).build())) {
            Inbox estimates = new Inbox(ClockMemberMain.ESTIMATED);
            Inbox fired = new Inbox(ClockMemberMain.FIRED);
            Inbox starts = new Inbox(Dtron.RUN_START);
            tester.addDtronListener(estimates);
            tester.addDtronListener(fired);
            tester.addDtronListener(starts);
            try (ChildJvm ahead = ChildJvm.start(ClockMemberMain.class, dir.resolve("ahead.log"), cluster, "ahead",
                    Long.toString(SHIFT_MILLIS), Integer.toString(port));
                    ChildJvm behind = ChildJvm.start(ClockMemberMain.class, dir.resolve("behind.log"), cluster,
                            "behind", Long.toString(-SHIFT_MILLIS), Integer.toString(port))) {
                Map<String, Long> shifts = Map.of("ahead", SHIFT_MILLIS * 1_000_000, "behind",
                        -SHIFT_MILLIS * 1_000_000);
                Map<String, IDtronChannelValued> byMember = new HashMap<>();
                for (int i = 0; i < 2; i++) {
                    IDtronChannelValued estimate = estimates.take();
                    byMember.put(estimate.getSender(), estimate);
                }
                assertEquals(shifts.keySet(), byMember.keySet(), ahead.output() + behind.output());
                for (IDtronChannelValued estimate : byMember.values()) {
                    String who = estimate.getSender();
                    // as the member read it, and as its message carries it on the wire
                    assertWithinBound(shifts.get(who), estimate.getVariables().get("offset_us") * 1_000L,
                            estimate.getVariables().get("error_us") * 1_000L + 1_000, who + " (variables)");
                    assertWithinBound(shifts.get(who), estimate.getClockOffsetNanos(),
                            estimate.getClockErrorNanos(), who + " (message fields)");
                }

                // a slow listener holds up RUN_START at the members; their run clocks still count from time 0
                // (a task due 10 units after the listener heard of the start would fire at 1800 ms)
                tester.send(ClockMemberMain.SLOW.constructValued(Map.of("millis", 800)));
                tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", (int) unitMicros)));
                long timeZero = starts.take().getEventTimeNanos();
                for (int i = 0; i < 2; i++) {
                    IDtronChannelValued fire = fired.take();
                    long arrived = fire.getReceiveTimeNanos() - timeZero;
                    long firedAt = fire.getEventTimeNanos() + fire.getClockOffsetNanos() - timeZero;
                    long error = fire.getClockErrorNanos();
                    String what = fire.getSender() + " fired at " + firedAt / 1e6 + " ms (arrived " + arrived / 1e6
                            + " ms, error " + error / 1e6 + " ms), due at " + fireAtNanos / 1e6 + " ms";
                    // not early beyond the estimate's error (and a little, as the estimate may have changed since)
                    assertTrue(arrived >= fireAtNanos - 2 * error - 10_000_000, what);
                    assertTrue(arrived <= fireAtNanos + 400_000_000, what);
                    assertTrue(Math.abs(firedAt - fireAtNanos) <= 2 * error + 300_000_000, what);
                }
                tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
                tester.send(ClockMemberMain.QUIT.constructValued(Map.of()));
                assertEquals(0, ahead.waitFor(Duration.ofSeconds(30)), ahead.output());
                assertEquals(0, behind.waitFor(Duration.ofSeconds(30)), behind.output());
            }
        }
    }

    /**
     * A member in a JVM of its own on this host reads the tester's very clock (one kernel, one boot id): its offset
     * is exactly 0, give or take the clock's microsecond, from its first estimate on, and its messages say so.
     */
    @Test
    void aMemberOnTheTestersHostHasAnExactOffset(@TempDir Path dir) throws Exception {
        String cluster = TestClusters.uniqueName("offsetHost");
        int port = FreePorts.range(FreePorts.BUS_RANGE);
        try (Dtron tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("tester")
                .port(port).portRange(FreePorts.BUS_RANGE).tester(true).build())) {
            Inbox estimates = new Inbox(ClockMemberMain.ESTIMATED);
            tester.addDtronListener(estimates);
            try (ChildJvm member = ChildJvm.start(ClockMemberMain.class, dir.resolve("member.log"), cluster, "member",
                    "0", Integer.toString(port))) {
                IDtronChannelValued estimate = estimates.take();
                assertEquals(0, estimate.getClockOffsetNanos(), member.output());
                assertEquals(1_000, estimate.getClockErrorNanos(), member.output());
                assertEquals(Map.of("offset_us", 0, "error_us", 1), estimate.getVariables());
                tester.send(ClockMemberMain.QUIT.constructValued(Map.of()));
                assertEquals(0, member.waitFor(Duration.ofSeconds(30)), member.output());
            }
        }
    }

    /** Sanity check of the test's own reading: unshifted members read the same clock as the test. */
    @Test
    void currentTimeIsTheWallClockPlusTheShift() {
        String cluster = TestClusters.uniqueName("shift");
        try (Dtron shifted = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster),
                Duration.ofMillis(SHIFT_MILLIS)).build())) {
            long difference = shifted.currentTimeNanos() - EpochClock.nowNanos();
            assertTrue(Math.abs(difference - SHIFT_MILLIS * 1_000_000) < 20_000_000, difference + " ns");
        }
    }
}
