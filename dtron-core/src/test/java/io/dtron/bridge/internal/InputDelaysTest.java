package io.dtron.bridge.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import java.util.Set;
import org.junit.jupiter.api.Test;

class InputDelaysTest {

    @Test
    void roundTripsAreSteadyWhenTheLastRoundsAreNoWorseThanTheOnesBefore() {
        // too few rounds to tell
        assertFalse(InputDelays.steady(List.of(500L, 500L, 500L, 500L, 500L, 500L, 500L, 500L, 500L)));
        // a fresh JVM: slow first rounds, then alike
        assertTrue(InputDelays.steady(List.of(57_000L, 20_000L, 9_000L, 600L, 500L, 400L, 500L, 450L, 500L, 480L,
                520L, 470L, 500L)));
        // a spike among the last rounds: not yet
        assertFalse(InputDelays.steady(List.of(4_000L, 4_000L, 4_000L, 4_000L, 4_000L, 4_000L, 4_000L, 6_100L,
                4_000L, 4_000L)));
        // 1.5 times the median of the rounds before is still steady
        assertTrue(InputDelays.steady(List.of(4_000L, 4_000L, 4_000L, 4_000L, 4_000L, 4_000L, 4_000L, 6_000L,
                4_000L, 4_000L)));
        // short round trips: within 1 ms of the median is steady, however many times it is
        assertTrue(InputDelays.steady(List.of(200L, 200L, 200L, 200L, 200L, 200L, 1_200L, 200L, 200L, 200L)));
        assertFalse(InputDelays.steady(List.of(200L, 200L, 200L, 200L, 200L, 200L, 1_201L, 200L, 200L, 200L)));
    }

    @Test
    void roundTripsNoLongerImproveWhenTheLastFiftyAreNotMuchFasterThanTheFiftyBefore() {
        List<Long> rounds = new java.util.ArrayList<>(java.util.Collections.nCopies(99, 3_000L));
        assertFalse(InputDelays.noLongerImproving(rounds), "too few rounds to tell");
        rounds.add(3_000L);
        assertTrue(InputDelays.noLongerImproving(rounds));
        // the compiler at work: the last fifty at 2.5 ms against 3 ms before, still getting faster
        rounds.addAll(java.util.Collections.nCopies(50, 2_500L));
        assertFalse(InputDelays.noLongerImproving(rounds));
        // 0.85 times the median before is no longer getting faster
        rounds.addAll(java.util.Collections.nCopies(50, 2_125L));
        assertTrue(InputDelays.noLongerImproving(rounds));
    }

    @Test
    void theRoomOfAChannelIsItsReceiversProbeOrTheHighPercentileOfItsAcknowledgedDelays() {
        InputDelays delays = new InputDelays();
        assertEquals(0, delays.roomMicros("start", Set.of()));
        delays.probed("adapter-a", 800);
        delays.probed("adapter-b", 3_000);
        assertEquals(800, delays.roomMicros("start", Set.of("adapter-a")));
        // nobody said it receives the channel: any member might
        assertEquals(3_000, delays.roomMicros("start", Set.of()));
        // acknowledged delays with their clock errors: the 99th percentile, when above the probe
        for (int i = 0; i < 99; i++) {
            delays.applied("start", 1_000, 100);
        }
        delays.applied("start", 50_000, 100);
        assertEquals(1_100, delays.roomMicros("start", Set.of("adapter-a")));
        delays.applied("start", 40_000, 100);
        assertEquals(40_100, delays.roomMicros("start", Set.of("adapter-a")));
        assertEquals(800, delays.roomMicros("stop", Set.of("adapter-a")));
    }

    @Test
    void anInputSentAheadNeedsRoomForHowLateItWasAppliedAndAddsToTheWayOnlyWhenItCameLate() {
        InputDelays delays = new InputDelays();
        delays.probed("adapter-a", 2_000);
        assertEquals(InputDelays.HELD_ROOM_MICROS, delays.heldRoomMicros("start"));
        // sent at 0, due at 5 ms, applied 20 us after it with a clock error of 10 us: on time
        for (int i = 0; i < 99; i++) {
            delays.appliedAhead("start", 0, 5_000, 5_020, 10);
        }
        assertEquals(InputDelays.HELD_ROOM_MICROS, delays.heldRoomMicros("start"));
        assertEquals(2_000, delays.roomMicros("start", Set.of("adapter-a")), "the hold is no part of the way");
        // one applied 3 ms after it was due: it arrived late, after a way of 8 ms; one such in 100 is no 99th
        // percentile, two are
        delays.appliedAhead("start", 0, 5_000, 8_000, 10);
        assertEquals(InputDelays.HELD_ROOM_MICROS, delays.heldRoomMicros("start"));
        assertEquals(8_010, delays.roomMicros("start", Set.of("adapter-a")));
        delays.appliedAhead("start", 0, 5_000, 8_000, 10);
        assertEquals(3_010, delays.heldRoomMicros("start"));
        assertEquals(8_010, delays.roomMicros("start", Set.of("adapter-a")));
    }
}
