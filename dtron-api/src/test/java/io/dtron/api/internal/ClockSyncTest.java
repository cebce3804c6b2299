package io.dtron.api.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ClockOffset;
import java.time.Duration;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import org.junit.jupiter.api.Test;

/**
 * A tester that reads the member's own clock (the same {@link HostClock} id) gives an exact offset, as long as the
 * round trips agree; a round trip that contradicts it, or another id, leaves the estimate to the round trips.
 */
class ClockSyncTest {
    private static final long MS = 1_000_000;

    /** A ping the member published: its sequence number and when it was sent on the member's clock. */
    private record Ping(long sequence, long sentAt, boolean probe) {
    }

    /** A pong the member published: the ping it answers. */
    private record Pong(String ackedSender, long ackedSequence) {
    }

    /** A member whose clock reads {@code now}, with the id {@code hostClock}, pinging the tester "t". */
    private static final class Member implements AutoCloseable {
        final AtomicLong now = new AtomicLong(1_000 * MS);
        final BlockingQueue<Ping> pings = new LinkedBlockingQueue<>();
        final BlockingQueue<Pong> pongs = new LinkedBlockingQueue<>();
        final AtomicLong sequence = new AtomicLong();
        final ClockSync sync;

        Member(String hostClock) {
            sync = new ClockSync("m", hostClock, false, now::get, sequence::incrementAndGet,
                    (channel, seq, publishTime, eventTime, ackedSender, ackedSequence, asInput, probe) -> {
                        if (channel.equals(ClockSync.PING)) {
                            pings.add(new Ping(seq, publishTime, probe));
                        } else if (channel.equals(ClockSync.PONG)) {
                            pongs.add(new Pong(ackedSender, ackedSequence));
                        }
                    }, () -> { });
            sync.start();
            sync.testerAnnounced("t", true);
        }

        /** Answers the next ping: the tester read {@code testerTime}, the pong arrived {@code roundTrip} after it. */
        Optional<ClockOffset> answer(long testerTime, long roundTrip, String testerHostClock)
                throws InterruptedException {
            Ping ping = pings.poll(10, TimeUnit.SECONDS);
            sync.pongReceived("t", "m", ping.sequence(), testerTime + ping.sentAt(), ping.sentAt() + roundTrip,
                    testerHostClock);
            return sync.estimate();
        }

        @Override
        public void close() {
            sync.close();
        }
    }

    @Test
    void aMemberAnswersItsTestersPingsAndAnyMembersProbeButNoOtherPing() throws InterruptedException {
        try (Member member = new Member("")) {
            assertFalse(member.pings.poll(10, TimeUnit.SECONDS).probe(), "a clock sample's ping is no probe");
            // a monitor's clock ping, then its probe, then the tester's ping: the pongs go out in that order
            member.sync.pingReceived("monitor", 7, 1, false, false);
            member.sync.pingReceived("monitor", 8, 2, false, true);
            member.sync.pingReceived("t", 9, 3, false, false);
            assertEquals(new Pong("monitor", 8), member.pongs.poll(10, TimeUnit.SECONDS));
            assertEquals(new Pong("t", 9), member.pongs.poll(10, TimeUnit.SECONDS));
            // its own probe asks every member
            Thread prober = new Thread(() -> {
                try {
                    member.sync.probe(List.of("x"), Duration.ofSeconds(10), false);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            });
            prober.start();
            Ping probe;
            do {
                probe = member.pings.poll(10, TimeUnit.SECONDS);
            } while (!probe.probe());
            assertTrue(member.sync.probeAnswered("x", "m", probe.sequence()));
            prober.join(10_000);
            assertFalse(prober.isAlive());
        }
    }

    @Test
    void aTesterReadingTheSameClockGivesAnExactOffset() throws InterruptedException {
        try (Member member = new Member("linux-boot:a")) {
            // the tester read the clock 0.3 ms into a 2 ms round trip: the same clock, offset 0 within a microsecond
            assertEquals(Optional.of(new ClockOffset("t", 0, ClockSync.SAME_CLOCK_SLACK_NANOS)),
                    member.answer(MS * 3 / 10, 2 * MS, "linux-boot:a"));
            assertEquals(Optional.of(new ClockOffset("t", 0, ClockSync.SAME_CLOCK_SLACK_NANOS)),
                    member.answer(2 * MS, 2 * MS, "linux-boot:a"));
        }
    }

    @Test
    void aRoundTripThatContradictsTheSameClockEndsItForGood() throws InterruptedException {
        try (Member member = new Member("linux-boot:a")) {
            member.answer(MS, 2 * MS, "linux-boot:a");
            // the tester's reading lies 5 ms after the pong arrived: not the member's clock
            Optional<ClockOffset> refuted = member.answer(7 * MS, 2 * MS, "linux-boot:a");
            assertEquals(MS, refuted.orElseThrow().errorNanos(), "half the best round trip");
            // later round trips that agree do not bring the claim back
            assertEquals(MS, member.answer(MS, 2 * MS, "linux-boot:a").orElseThrow().errorNanos());
        }
    }

    @Test
    void anotherClockOrNoneIsEstimatedFromRoundTrips() throws InterruptedException {
        try (Member member = new Member("linux-boot:a")) {
            assertEquals(Optional.of(new ClockOffset("t", 0, MS)), member.answer(MS, 2 * MS, "linux-boot:b"));
        }
        try (Member member = new Member("")) {
            assertEquals(Optional.of(new ClockOffset("t", 0, MS)), member.answer(MS, 2 * MS, ""));
        }
    }
}
