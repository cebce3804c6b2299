package io.dtron.engine.internal.tester;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;

import io.dtron.engine.internal.verify.DiscreteGraph;
import io.dtron.engine.verify.Query;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.util.BitSet;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The coverage strategy's table of moves that cover every target left, on a graph small enough to count by hand: from
 * Start, a loop of three moves Start -> P1 -> P2 -> Start whose last edge is target T2, and a one-way edge T1 to a dead
 * end. Covering both takes four moves, the loop first; taking T1 first strands T2.
 */
class CoverTableTest {
    private static final String MODEL = """
            process P() {
                state Start, P1, P2, Dead;
                init Start;
                trans Start -> P1 { },
                      P1 -> P2 { },
                      P2 -> Start { },
                      Start -> Dead { };
            }
            system P;
            """;

    /** Global edge numbers of the model (one process, so in the order written). */
    private static final int LOOP_1 = 0;
    private static final int T2 = 2;
    private static final int T1 = 3;

    private static DiscreteGraph.Arc arc(DiscreteGraph g, int from, int edge) {
        for (DiscreteGraph.Arc a : g.arcs(from)) {
            if (a.edges().length == 1 && a.edges()[0] == edge) {
                return a;
            }
        }
        throw new AssertionError("no arc of edge " + edge + " from node " + from);
    }

    @Test
    void theLoopFirstCoversBothInFourMoves() throws Exception {
        Network n = ModelLoader.load("model.xta", MODEL);
        DiscreteGraph g = DiscreteGraph.explore(n, List.of(), 1000);
        assertEquals(4, g.size());
        BitSet targets = new BitSet();
        targets.set(T1);
        targets.set(T2);
        int horizon = 3;
        CoverTable table = CoverTable.of(g, targets, new BitSet(), horizon);
        int both = table.maskOf(targets, new BitSet());
        int start = 0;
        DiscreteGraph.Arc intoLoop = arc(g, start, LOOP_1);
        DiscreteGraph.Arc t1 = arc(g, start, T1);
        // into the loop: 1 move, then P1 -> P2, T2 (back at Start), T1: 1 + 3
        assertEquals(4, table.score(intoLoop, both));
        // T1 first: 1 move, then T2 cannot be covered from the dead end: given up at the horizon plus one, 1 + 4
        assertEquals(5, table.score(t1, both));
        // the sum of separate distances would prefer T1: 0 for T1 plus T2 capped at 4, against 4 (the move to P1, then
        // P2, Start, T1) plus 3 (the move to P1, then P2, T2)

        // once T2 is covered, the table of the smaller set is in the same table: T1 first is then best
        BitSet onlyT1 = new BitSet();
        onlyT1.set(T1);
        int one = table.maskOf(onlyT1, new BitSet());
        assertEquals(1, table.score(t1, one));
        assertEquals(4, table.score(intoLoop, one)); // P1 -> P2, T2, T1
        int p1 = intoLoop.target();
        assertEquals(3, table.score(arc(g, p1, 1), one)); // P1 -> P2, then T2, T1
        assertEquals(0, g.arcs(t1.target()).length, "a dead end");
    }

    @Test
    void anArcFromWhichNoTargetIsWithinTheHorizonIsUnreachable() throws Exception {
        Network n = ModelLoader.load("model.xta", MODEL);
        DiscreteGraph g = DiscreteGraph.explore(n, List.of(), 1000);
        BitSet targets = new BitSet();
        targets.set(T2);
        CoverTable table = CoverTable.of(g, targets, new BitSet(), 3);
        int left = table.maskOf(targets, new BitSet());
        assertEquals(DiscreteGraph.UNREACHABLE, table.score(arc(g, 0, T1), left));
        assertEquals(3, table.score(arc(g, 0, LOOP_1), left));
        // within a horizon of 1 the loop's last edge is still 3 moves away: given up, but Start -> P1 still scores
        // as much as giving it up (the horizon plus one, plus its own move) and not better: unreachable as well
        CoverTable near = CoverTable.of(g, targets, new BitSet(), 1);
        assertEquals(DiscreteGraph.UNREACHABLE, near.score(arc(g, 0, LOOP_1), near.maskOf(targets, new BitSet())));
    }

    @Test
    void aTargetNotInTheTableHasNoMask() throws Exception {
        Network n = ModelLoader.load("model.xta", MODEL);
        DiscreteGraph g = DiscreteGraph.explore(n, List.of(), 1000);
        BitSet targets = new BitSet();
        targets.set(T1);
        CoverTable table = CoverTable.of(g, targets, new BitSet(), 3);
        BitSet other = new BitSet();
        other.set(T2);
        assertEquals(-1, table.maskOf(other, new BitSet()));
        assertSame(table, CoverTable.of(g, targets, new BitSet(), 3), "built once per graph, targets and horizon");
    }

    @Test
    void goalsAreTargetsAsWell() throws Exception {
        Network n = ModelLoader.load("model.xta", MODEL);
        DiscreteGraph g = DiscreteGraph.explore(n, List.of(Query.parse("E<> P.P2"), Query.parse("E<> P.Dead")),
                1000);
        BitSet goals = new BitSet();
        goals.set(0);
        goals.set(1);
        CoverTable table = CoverTable.of(g, new BitSet(), goals, 3);
        int both = table.maskOf(new BitSet(), goals);
        // Start -> P1, P1 -> P2 (goal 0), P2 -> Start, Start -> Dead (goal 1)
        assertEquals(4, table.score(arc(g, 0, LOOP_1), both));
        assertEquals(5, table.score(arc(g, 0, T1), both));
    }

    @Test
    void tooManyTargetsHaveNoTable() throws Exception {
        Network n = ModelLoader.load("model.xta", MODEL);
        DiscreteGraph g = DiscreteGraph.explore(n, List.of(), 1000);
        assertNull(CoverTable.of(g, new BitSet(), new BitSet(), 3), "no targets");
        BitSet many = new BitSet();
        many.set(0, CoverTable.MAX_TARGETS + 1);
        assertNull(CoverTable.of(g, many, new BitSet(), 3));
    }
}
