package io.dtron.engine.internal.sem;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.zone.Bound;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The tester's extrapolation per state: a clock no process compares with a constant before resetting it is free
 * (its value can no longer matter), the others keep their relations up to the bounds of their locations, and the
 * tester's elapsed clock stays exact.
 */
class ExtrapolationTest {
    private static final int TICKS = 1000;
    /** Two timers: x0 and x1 matter while their timer is Set (fires 2 to 10 units after), not while Idle. */
    private static final String TIMERS = """
            chan i_set, o_fire0, o_fire1;
            process Env() { state E; init E; trans E -> E { sync i_set!; }, E -> E { sync o_fire0?; },
                E -> E { sync o_fire1?; }; }
            process T0() { clock x0; state Idle, Set { x0 <= 10 }; init Idle;
                trans Idle -> Set { sync i_set?; assign x0 = 0; }, Set -> Idle { guard x0 >= 2; sync o_fire0!; }; }
            process T1() { clock x1; state Idle, Set { x1 <= 10 }; init Idle;
                trans Idle -> Set { sync i_set?; assign x1 = 0; }, Set -> Idle { guard x1 >= 2; sync o_fire1!; }; }
            system Env, T0, T1;
            """;

    @Test
    void idleTimersClocksAreFreeAndSetOnesKeepTheirRelationToTheElapsedClock() throws Exception {
        Network network = ModelLoader.load("timers.xta", TIMERS);
        Semantics semantics = new Semantics(network, TICKS);
        int x0 = network.clocks().get(0).index();
        int x1 = network.clocks().get(1).index();
        int elapsed = semantics.elapsedClock();

        SymState idle = semantics.initial();
        semantics.delay(idle);
        // before extrapolation the clocks run together: x0 - elapsed == 0
        assertEquals(Bound.le(0), idle.zone().upperBound(x0, elapsed));
        semantics.extrapolate(idle);
        assertEquals(Bound.INFINITY, idle.zone().upperBound(x0, elapsed), "x0 is free while T0 is idle");
        assertEquals(Bound.INFINITY, idle.zone().upperBound(x1, elapsed), "x1 is free while T1 is idle");
        assertEquals(Bound.le(0), idle.zone().upperBound(0, elapsed), "elapsed >= 0, exact as before");

        // one input sets one of the timers: in that successor its clock keeps its exact relation to elapsed
        List<SymState> set = new ArrayList<>();
        semantics.moves(idle, (move, next) -> {
            if (semantics.delay(next)) {
                set.add(next);
            }
        });
        SymState t0Set = set.stream().filter(s -> s.location(1) == 1 && s.location(2) == 0).findFirst()
                .orElseThrow();
        semantics.extrapolate(t0Set);
        assertNotEquals(Bound.INFINITY, t0Set.zone().upperBound(x0, 0), "x0 <= 10 while T0 is set");
        assertEquals(Bound.le(10 * TICKS), t0Set.zone().upperBound(x0, 0));
        assertEquals(Bound.INFINITY, t0Set.zone().upperBound(x1, elapsed), "x1 is still free: T1 is idle");
        assertTrue(t0Set.zone().upperBound(x0, elapsed) != Bound.INFINITY,
                "x0 - elapsed is kept: the windows of fire0 are read from it");
    }
}
