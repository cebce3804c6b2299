package io.dtron.engine.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.verify.VerificationResult.Outcome;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import org.junit.jupiter.api.Test;

/**
 * {@code E[]}, {@code A<>} and {@code -->} with clock constraints and {@code deadlock} in their properties, on
 * small models whose answers are worked out by hand next to each query. A path inside a property satisfies it at
 * every instant, delays included; counterexamples replay in the engine.
 */
class LivenessTest {
    /** P must leave a (x <= 10) for b once x >= 3; in b nothing happens and time passes for ever. */
    private static final String GROW = """
            clock x;
            process P() {
                state a { x <= 10 }, b;
                init a;
                trans a -> b { guard x >= 3; };
            }
            system P;
            """;

    /** As GROW, but a may also go, while x < 1, to c, where time stops at x == 2 and nothing can happen. */
    private static final String STOP = """
            clock x;
            process P() {
                state a { x <= 10 }, b, c { x <= 2 };
                init a;
                trans a -> b { guard x >= 3; }, a -> c { guard x < 1; }, b -> b { guard x >= 5; assign x := 0; };
            }
            system P;
            """;

    private static VerificationResult check(String model, String query) throws Exception {
        Network n = ModelLoader.load("model.xta", model);
        return new Verifier(n, VerifierOptions.defaults()).verify(Query.parse(query));
    }

    private static Outcome answer(String model, String query) throws Exception {
        return check(model, query).outcome();
    }

    /** The answer is {@code VIOLATED} and its counterexample ends as {@code end} says and replays in the engine. */
    private static Trace violated(String model, String query, String end) throws Exception {
        VerificationResult r = check(model, query);
        assertEquals(Outcome.VIOLATED, r.outcome(), query);
        Trace t = r.trace();
        assertTrue(t.end().startsWith(end), t.end() + "\n" + t.toText());
        EngineCrossCheckTest.replay(ModelLoader.load("model.xta", model), t);
        return t;
    }

    @Test
    void timeThatMustPassReachesEveryClockBound() throws Exception {
        // every path leaves a by x == 10 at the latest, through x >= 3, and then lets time pass for ever in b:
        // x grows without bound, so it reaches 5 and passes 10 on every path
        assertEquals(Outcome.SATISFIED, answer(GROW, "A<> x >= 5"));
        assertEquals(Outcome.SATISFIED, answer(GROW, "A<> x > 10"));
        assertEquals(Outcome.SATISFIED, answer(GROW, "A<> P.b and x > 10"));
        // x is continuous: every path passes through the instant x == 4, though no move happens there
        assertEquals(Outcome.SATISFIED, answer(GROW, "A<> x == 4"));
        // a path that takes the edge at x >= 4 is never in b with x < 4: it ends with time passing for ever
        violated(GROW, "A<> P.b and x < 4", "time passing forever");
    }

    @Test
    void aPathInsideAPropertyStaysInsideAtEveryInstant() throws Exception {
        // a must be left with x >= 3, and b lets x grow past any bound
        assertEquals(Outcome.VIOLATED, answer(GROW, "E[] x < 3"));
        assertEquals(Outcome.VIOLATED, answer(GROW, "E[] x <= 3"));
        // true at every instant only if x never equals 4: but x runs through 4 on every path
        assertEquals(Outcome.VIOLATED, answer(GROW, "E[] x < 4 or x > 4"));
        // wait in a until x > 7, then b: x stays above 7 from then on; any path starts at x == 0, where x > 7 fails
        VerificationResult late = check(GROW, "E[] P.a or x > 7");
        assertEquals(Outcome.SATISFIED, late.outcome());
        // the concrete witness keeps to the property too: it moves to b after x == 7
        assertTrue(late.trace().concrete().get(0).time().compareTo(java.math.BigDecimal.valueOf(7)) > 0,
                late.trace().toText());
        EngineCrossCheckTest.replay(ModelLoader.load("model.xta", GROW), late.trace());
        assertEquals(Outcome.VIOLATED, answer(GROW, "E[] x > 7"));
        // entering b with x <= 7 leaves the property at that instant
        assertEquals(Outcome.VIOLATED, answer(GROW, "E[] P.a or x > 7 and x < 12"));
    }

    @Test
    void aDelayMayPassFromOneZoneOfThePropertyToAnother() throws Exception {
        // s is left at x == 2 with x reset: in a, y == x + 2 for ever, and time passes for ever
        String shifted = """
                clock x, y;
                process P() {
                    state s { x <= 2 }, a;
                    init s;
                    trans s -> a { guard x == 2; assign x := 0; };
                }
                system P;
                """;
        // in a, x < 2 or y > 3 is x < 2 or x > 1: always true, though neither zone holds the whole delay
        VerificationResult across = check(shifted, "E[] P.s or x < 2 or y > 3");
        assertEquals(Outcome.SATISFIED, across.outcome());
        assertEquals("time passing forever", across.trace().end(), across.trace().toText());
        // x < 1 or y > 3 is x < 1 or x > 1: the instant x == 1 is outside
        assertEquals(Outcome.VIOLATED, answer(shifted, "E[] P.s or x < 1 or y > 3"));
        assertEquals(Outcome.SATISFIED, answer(shifted, "P.a --> x == 1 or x > 5"));
        assertEquals(Outcome.SATISFIED, answer(shifted, "A<> P.a and x >= 1 and y <= 3"));
    }

    @Test
    void aZenoLoopOrADeadlockKeepsAPathBelowABound() throws Exception {
        String zeno = """
                clock x;
                process P() {
                    state a { x <= 10 }, b;
                    init a;
                    trans a -> a { guard x < 2; }, a -> b { guard x >= 3; };
                }
                system P;
                """;
        // the loop on a can be taken for ever at x == 0, without time passing (a maximal path, as in Uppaal)
        VerificationResult loop = check(zeno, "E[] x < 3");
        assertEquals(Outcome.SATISFIED, loop.outcome());
        assertTrue(loop.trace().end().startsWith("a cycle back to state"), loop.trace().end());
        // going to c at x < 1 ends the path in a deadlock, below 3 for good
        VerificationResult dead = check(STOP, "E[] x < 3");
        assertEquals(Outcome.SATISFIED, dead.outcome());
        assertEquals("a deadlock", dead.trace().end(), dead.trace().toText());
        assertEquals("P.c", dead.trace().states().get(dead.trace().states().size() - 1).locations().get(0));
    }

    @Test
    void leadsToWithClockConstraints() throws Exception {
        // from any instant in a, the path either waits in a (past 2 on its way to 3) or leaves at x >= 3
        assertEquals(Outcome.SATISFIED, answer(GROW, "P.a --> x > 2"));
        // from b with x <= 5, time passes for ever: x reaches 6
        assertEquals(Outcome.SATISFIED, answer(GROW, "P.b and x <= 5 --> x > 5"));
        // through c the path stops in a deadlock with x < 1, and time cannot pass 2 there
        violated(STOP, "P.a --> x > 2", "a deadlock");
        // in b, x is reset each time it reaches 5 (or more): from x == 6 in b, x > 7 may never happen
        Trace loop = violated(STOP, "P.b and x > 5 --> x > 7", "a cycle back to state");
        // the concrete counterexample starts where the premise holds: the loop is first taken with 5 < x <= 7
        java.math.BigDecimal x = loop.concrete().get(1).clocks().get("x");
        assertTrue(x.compareTo(java.math.BigDecimal.valueOf(5)) > 0 && x.compareTo(java.math.BigDecimal.valueOf(7))
                <= 0, loop.toText());
        // b has no invariant: time may pass there for ever without taking the loop, so x == 0 is not forced
        violated(STOP, "P.b and x > 5 --> x == 0", "time passing forever");
    }

    @Test
    void deadlockInLivenessProperties() throws Exception {
        // b has no edge: every path ends there, deadlocked (a must be left by x == 10, towards b)
        assertEquals(Outcome.SATISFIED, answer(GROW, "A<> deadlock"));
        assertEquals(Outcome.VIOLATED, answer(GROW, "E[] not deadlock"));
        // b has a loop but no invariant: time may pass there for ever, never deadlocked
        Trace t = violated(STOP, "A<> deadlock", "time passing forever");
        assertEquals("P.b", t.states().get(t.states().size() - 1).locations().get(0));
        assertEquals(Outcome.SATISFIED, answer(STOP, "E[] not deadlock"));
        // c is a deadlock from its entry (x < 1) on; a path through it lets time pass up to x == 2 and stops
        assertEquals(Outcome.SATISFIED, answer(STOP, "P.a --> deadlock or P.b"));
        // c with 1 <= x <= 2 is reachable too (time passes in c), and there x < 1 is over for good
        violated(STOP, "P.c --> deadlock and x < 1", "a deadlock");
        assertEquals(Outcome.SATISFIED, answer(STOP, "P.c --> x >= 2"));
        violated(STOP, "P.c --> x > 2", "a deadlock");
    }

    @Test
    void aPathEndsOnlyWhereNeitherAMoveNorADelayIsPossible() throws Exception {
        String timeLock = """
                clock x;
                process P() {
                    state a { x <= 10 };
                    init a;
                }
                system P;
                """;
        // nothing can ever happen in a, but time passes up to the invariant's bound: the only maximal path is the
        // delay from x == 0 to x == 10, deadlocked all along, and it ends there
        assertEquals(Outcome.SATISFIED, answer(timeLock, "A<> x >= 5"));
        assertEquals(Outcome.SATISFIED, answer(timeLock, "A<> x == 10 and deadlock"));
        assertEquals(Outcome.VIOLATED, answer(timeLock, "E[] x < 10"));
        VerificationResult whole = check(timeLock, "E[] x <= 10");
        assertEquals(Outcome.SATISFIED, whole.outcome());
        assertEquals("a deadlock", whole.trace().end());
        // the concrete witness lets time pass up to where the path stops
        assertEquals(0, whole.trace().concrete().get(0).time().compareTo(java.math.BigDecimal.TEN),
                whole.trace().toText());
        // GROW's b is a deadlock too (no edge), but time passes there for ever: it is no end before x >= 5
        assertEquals(Outcome.VIOLATED, answer(GROW, "E[] x < 5"));
    }

    @Test
    void uppaalExamplesWithClocksInLivenessProperties() throws Exception {
        // the liveness queries in the examples' own <queries> (train-gate-utap.xml: Train(i).Appr -->
        // Train(i).Cross) mention locations only, and were answered before; these mention clocks
        Network trains = UppaalExamplesTest.example("train-gate.xml");
        // a train in Cross stays until x >= 3 (its only way out), and Cross is left by x <= 5: time must pass
        // there (no Zeno loop in the model: every round of a train takes time), so x >= 3 comes on every path
        assertEquals(Outcome.SATISFIED, verify(trains, "Train(0).Appr --> Train(0).Cross and Train(0).x >= 3"));
        // a train stopped as it approaches (x == 0) leaves Appr below 10, crosses later through Start, and
        // may then stay Safe for ever: it need not be in Appr with x >= 10 again
        Trace stopped = trace(trains, "Train(0).Appr --> Train(0).Appr and Train(0).x >= 10");
        assertEquals("time passing forever", stopped.end(), stopped.toText());
        // train 0 may go round (Appr, Cross, Safe, Appr at once) for ever: x never passes 20 (Appr's invariant)
        assertEquals(Outcome.SATISFIED, verify(trains, "E[] Train(0).x <= 20"));
        Trace round = trace(trains, "A<> Train(0).x > 20");
        assertTrue(round.end().startsWith("a cycle back to state"), round.toText());

        Network doors = UppaalExamplesTest.example("2doors.xml");
        // open is entered from opening with x reset to 0, at that instant
        assertEquals(Outcome.SATISFIED, verify(doors, "Door1.opening --> Door1.open and Door1.x == 0"));
        // closing (x <= 6) is left only at x == 6, and time is not blocked there: x reaches 6 in closing
        assertEquals(Outcome.SATISFIED, verify(doors, "Door1.open --> Door1.closing and Door1.x >= 6"));
        // open may be left at x == 4, and the door may then stay idle for ever (the user need not push)
        Trace early = trace(doors, "Door1.open --> Door1.open and Door1.x >= 5");
        assertEquals("time passing forever", early.end(), early.toText());
    }

    private static Outcome verify(Network n, String query) {
        return new Verifier(n, VerifierOptions.defaults()).verify(Query.parse(query)).outcome();
    }

    /** The counterexample of a violated query, replayed in the engine. */
    private static Trace trace(Network n, String query) {
        VerificationResult r = new Verifier(n, VerifierOptions.defaults()).verify(Query.parse(query));
        assertEquals(Outcome.VIOLATED, r.outcome(), query);
        EngineCrossCheckTest.replay(n, r.trace());
        return r.trace();
    }
}
