package io.dtron.engine.internal.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotSame;
import static org.junit.jupiter.api.Assertions.assertSame;

import io.dtron.engine.verify.Query;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.util.BitSet;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The planner's graph of a user who presses and a system that answers 3 to 5 units later: its nodes and distances
 * counted by hand, and one exploration per network and goals, shared by the runs that ask again.
 */
class DiscreteGraphTest {
    private static final String MODEL = """
            chan i_press, o_answer;
            process Sys() {
                clock x;
                state Idle, Busy { x <= 5 };
                init Idle;
                trans Idle -> Busy { sync i_press?; assign x = 0; },
                      Busy -> Idle { guard x >= 3; sync o_answer!; };
            }
            process User() {
                clock y;
                state Ready, Waiting;
                init Ready;
                trans Ready -> Waiting { guard y >= 100; sync i_press!; },
                      Waiting -> Ready { sync o_answer?; assign y = 0; };
            }
            system Sys, User;
            """;

    @Test
    void twoNodesAndTheMovesBetweenThem() throws Exception {
        Network n = ModelLoader.load("model.xta", MODEL);
        DiscreteGraph g = DiscreteGraph.explore(n, List.of(Query.parse("E<> Sys.Busy")), 1000);
        assertEquals(2, g.size());
        assertEquals(true, g.complete());
        DiscreteGraph.Arc answer = g.arcs(1)[0];
        int[] moves = g.distances(new BitSet(), a -> a == answer);
        assertEquals(List.of(2, 1), List.of(moves[0], moves[1]));
        assertEquals(List.of(1, 0), List.of(g.distances(g.goalNodes(0), null)[0], g.distances(g.goalNodes(0),
                null)[1]));
    }

    @Test
    void theSameNetworkTowardTheSameGoalsIsExploredOnce() throws Exception {
        Network n = ModelLoader.load("model.xta", MODEL);
        DiscreteGraph first = DiscreteGraph.cached(n, List.of(), 1000);
        assertSame(first, DiscreteGraph.cached(n, List.of(), 1000));
        Network other = ModelLoader.load("model.xta", MODEL);
        DiscreteGraph second = DiscreteGraph.cached(other, List.of(), 1000);
        assertNotSame(first, second, "another network (an equal one too)");
        assertNotSame(second, DiscreteGraph.cached(other, List.of(Query.parse("E<> Sys.Busy")), 1000),
                "other goals");
    }
}
