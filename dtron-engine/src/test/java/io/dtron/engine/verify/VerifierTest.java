package io.dtron.engine.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.verify.VerificationResult.Outcome;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.math.BigDecimal;
import java.time.Duration;
import java.util.List;
import org.junit.jupiter.api.Test;

/** Known answers on small models of the tests' own: Fischer's protocol, right and wrong, and liveness. */
class VerifierTest {
    private static final String MUTEX = "A[] forall (i : pid_t) forall (j : pid_t) P(i).cs && P(j).cs imply i == j";

    static Network load(String name) throws Exception {
        return ModelLoader.loadResource(VerifierTest.class.getClassLoader(), "io/dtron/engine/verify/" + name);
    }

    static VerificationResult check(Network n, String query) {
        return new Verifier(n, VerifierOptions.defaults()).verify(Query.parse(query));
    }

    @Test
    void fischerIsMutuallyExclusiveWhenProcessesWaitLongerThanTheyMayTakeToRequest() throws Exception {
        VerificationResult r = check(load("fischer.xta"), MUTEX);
        assertEquals(Outcome.SATISFIED, r.outcome());
        assertNull(r.trace(), "a satisfied A[] has no trace");
        assertTrue(r.statistics().explored() > 10, r.statistics().toString());
        assertTrue(r.statistics().stored() > 10, r.statistics().toString());
    }

    @Test
    void fischerWithTooShortAWaitLetsTwoProcessesIntoTheCriticalSectionAndSaysHow() throws Exception {
        VerificationResult r = check(load("fischer-wrong.xta"), MUTEX);
        assertEquals(Outcome.VIOLATED, r.outcome());
        Trace t = r.trace();
        assertNotNull(t);
        List<String> last = t.states().get(t.states().size() - 1).locations();
        assertEquals(2, last.stream().filter(l -> l.endsWith(".cs")).count(), last.toString());
        // breadth-first: the shortest counterexample. Both read id == 0 and request, the first writes its id and
        // waits, the second writes its id later (within REQ = 2), the first enters after more than WAIT = 1, then
        // the second after more than 1 more: six moves.
        assertEquals(6, t.transitions().size(), t.toText());
        assertEquals(t.transitions().size() + 1, t.concrete().size(), t.toText());
        BigDecimal end = t.concrete().get(t.concrete().size() - 1).time();
        assertTrue(end.compareTo(BigDecimal.ONE) > 0, "entering takes more than WAIT: " + t.toText());
        for (Trace.ConcreteStep step : t.concrete()) {
            assertTrue(step.delay().signum() >= 0, t.toText());
        }
        String json = t.toJson();
        assertTrue(json.startsWith("{\"states\":[{\"locations\":[\"P(1).idle\""), json);
        assertTrue(json.contains("\"concrete\":[{\"delay\":0"), json);
        assertTrue(t.toText().contains("concrete:"), t.toText());
    }

    @Test
    void reachabilityWitnessesEndWhereThePropertyHoldsIncludingItsClockConstraint() throws Exception {
        Network n = load("fischer.xta");
        VerificationResult r = check(n, "E<> P(1).cs && P(1).x > 5");
        assertEquals(Outcome.SATISFIED, r.outcome());
        Trace t = r.trace();
        assertTrue(t.states().get(t.states().size() - 1).zone().contains("P(1).x>5"), t.toText());
        Trace.ConcreteStep last = t.concrete().get(t.concrete().size() - 1);
        assertTrue(last.clocks().get("P(1).x").compareTo(BigDecimal.valueOf(5)) > 0, t.toText());
        assertEquals(Outcome.VIOLATED, check(n, "E<> P(1).req && P(1).x > 2").outcome(), "the invariant x <= REQ");
        assertEquals(Outcome.SATISFIED, check(n, "A[] P(1).req imply P(1).x <= 2").outcome());
    }

    @Test
    void fischerHasNoDeadlockButAModelThatStopsHasOne() throws Exception {
        assertEquals(Outcome.SATISFIED, check(load("fischer.xta"), "A[] not deadlock").outcome());
        Network stops = ModelLoader.load("stops.xta", """
                clock x;
                process P() { state a { x <= 3 }, b; init a; trans a -> b { guard x >= 2; }; }
                system P;
                """);
        VerificationResult r = check(stops, "A[] not deadlock");
        assertEquals(Outcome.VIOLATED, r.outcome(), "in b nothing can happen any more");
        assertEquals("P.b", r.trace().states().get(1).locations().get(0));
        // a guard that can be missed: x < 2 with no invariant, so waiting past 2 in a is a deadlock too
        Network late = ModelLoader.load("late.xta", """
                clock x;
                process P() { state a, b; init a; trans a -> b { guard x < 2; }, b -> a { assign x = 0; }; }
                system P;
                """);
        VerificationResult missed = check(late, "E<> deadlock");
        assertEquals(Outcome.SATISFIED, missed.outcome());
        assertTrue(missed.trace().states().get(missed.trace().states().size() - 1).zone().contains("x>=2"),
                missed.trace().toText());
    }

    @Test
    void livenessFollowsUppaalsMaximalPaths() throws Exception {
        Network n = load("fischer.xta");
        // req has the invariant x <= REQ and one way out, to wait
        assertEquals(Outcome.SATISFIED, check(n, "P(1).req --> P(1).wait").outcome());
        // P(2) may stay in its critical section for ever: P(1) then waits for ever
        VerificationResult starve = check(n, "P(1).wait --> P(1).cs");
        assertEquals(Outcome.VIOLATED, starve.outcome());
        assertEquals("time passing forever", starve.trace().end(), starve.trace().toText());
        // nothing forces P(1) out of idle
        VerificationResult idle = check(n, "A<> P(1).cs");
        assertEquals(Outcome.VIOLATED, idle.outcome());
        assertEquals(1, idle.trace().states().size(), idle.trace().toText());
        assertEquals(Outcome.SATISFIED, check(n, "E[] P(1).idle").outcome());
        assertEquals(Outcome.SATISFIED, check(n, "A<> true").outcome());
        assertEquals(Outcome.VIOLATED, check(n, "E[] P(1).req").outcome(), "req must be left within REQ");
    }

    @Test
    void zenoCyclesCountAsInfinitePathsAsInUppaal() throws Exception {
        Network n = ModelLoader.load("zeno.xta", """
                clock x;
                process P() {
                    state a { x <= 5 }, done;
                    init a;
                    trans a -> a { }, a -> done { guard x >= 5; };
                }
                system P;
                """);
        VerificationResult r = check(n, "A<> P.done");
        assertEquals(Outcome.VIOLATED, r.outcome(), "the loop on a can run for ever without time passing");
        assertEquals(0, r.trace().loopStart(), r.trace().toText());
        assertTrue(r.trace().end().startsWith("a cycle back to state 0"), r.trace().end());
    }

    @Test
    void committedLocationsUrgentChannelsAndBroadcastsAreTheEnginesOwn() throws Exception {
        Network n = ModelLoader.load("sync.xta", """
                clock x;
                urgent chan u;
                broadcast chan b;
                int got = 0;
                process S() { state s0, s1, s2 { x <= 10 }, s3; commit s1; init s0;
                    trans s0 -> s1 { guard x >= 1; }, s1 -> s2 { sync u!; }, s2 -> s3 { sync b!; assign x = 0; }; }
                process R() { state r0, r1; init r0; trans r0 -> r1 { sync u?; }; }
                process Q(const int k) { state q0, q1; init q0; trans q0 -> q1 { sync b?; assign got = got + k; }; }
                Q1 = Q(1); Q2 = Q(2);
                system S, R, Q1, Q2;
                """);
        assertEquals(Outcome.SATISFIED, check(n, "E<> got == 3").outcome(), "both receivers of the broadcast");
        assertEquals(Outcome.VIOLATED, check(n, "E<> got == 1").outcome(), "a broadcast takes every receiver");
        // s1 is committed: no time passes there, so x is still what it was when s0 was left
        assertEquals(Outcome.SATISFIED, check(n, "A[] S.s1 imply x >= 1").outcome());
        // u is urgent and R is ready: s2 is entered at once after s1, with no delay
        VerificationResult r = check(n, "E<> S.s3");
        assertEquals(Outcome.SATISFIED, r.outcome());
        List<Trace.ConcreteStep> c = r.trace().concrete();
        assertEquals(BigDecimal.ZERO, c.get(1).delay(), r.trace().toText());
        assertEquals(BigDecimal.ZERO, c.get(2).delay(), r.trace().toText());
    }

    @Test
    void searchOrderChangesTheTraceNotTheAnswer() throws Exception {
        Network n = load("fischer-wrong.xta");
        Verifier dfs = new Verifier(n, VerifierOptions.defaults().withOrder(SearchOrder.DEPTH_FIRST));
        VerificationResult r = dfs.verify(Query.parse(MUTEX));
        assertEquals(Outcome.VIOLATED, r.outcome());
        assertTrue(r.trace().transitions().size() >= 6, r.trace().toText());
    }

    @Test
    void aTimeLimitGivesAnHonestUnknown() throws Exception {
        Network n = ModelLoader.load("grows.xta", """
                int[0,30000] i = 0;
                process P() { state a; init a; trans a -> a { guard i < 30000; assign i = i + 1; }; }
                system P;
                """);
        Verifier v = new Verifier(n, VerifierOptions.defaults().withTimeLimit(Duration.ZERO));
        VerificationResult r = v.verify(Query.parse("A[] i < 30000"));
        assertEquals(Outcome.UNKNOWN, r.outcome());
        assertTrue(r.reason().contains("time limit"), r.reason());
    }

    @Test
    void queriesThatAreNotSymbolicAreSkippedWithTheReason() {
        for (String q : List.of("Pr[<=10](<> P.a)", "simulate [<=10] { x }", "E[<=10; 100](max: x)",
                "sup: x", "inf{P.a}: x", "control: A[] P.a", "strategy s = A<> P.a", "E<> P.a under s")) {
            Query parsed = Query.parse(q);
            assertEquals(Query.Kind.UNSUPPORTED, parsed.kind(), q);
            assertNotNull(parsed.reason(), q);
        }
        assertEquals(Query.Kind.LEADS_TO, Query.parse("P.a --> (P.b)").kind());
        assertEquals(Query.Kind.EXISTS_GLOBALLY, Query.parse("E [] P.a").kind());
    }

    @Test
    void aBadQueryNamesItselfAndThePlace() throws Exception {
        QueryException notAQuery = assertThrows(QueryException.class, () -> Query.parse("P.a"));
        assertTrue(notAQuery.getMessage().startsWith("query 'P.a', column 1: not a query"), notAQuery.getMessage());
        Network n = load("fischer.xta");
        QueryException syntax = assertThrows(QueryException.class, () -> check(n, "E<> P(1).cs &&"));
        assertTrue(syntax.getMessage().startsWith("query 'E<> P(1).cs &&', column "), syntax.getMessage());
        QueryException unknown = assertThrows(QueryException.class, () -> check(n, "E<> P(1).cs and foo > 1"));
        assertEquals("query 'E<> P(1).cs and foo > 1', column 17: unknown name 'foo'", unknown.getMessage());
        QueryException noLocation = assertThrows(QueryException.class, () -> check(n, "E<> P(1).nowhere"));
        assertTrue(noLocation.getMessage().contains("process P(1) has no location or variable 'nowhere'"),
                noLocation.getMessage());
        // in a file, a bad query is its own INVALID entry, with its line; the others are kept and can be checked
        List<Query> file = Query.parseFile("""
                // three queries
                E<> P(1).cs

                oops
                E<> P(1).cs and foo > 1
                """);
        assertEquals(List.of(Query.Kind.EXISTS_EVENTUALLY, Query.Kind.INVALID, Query.Kind.EXISTS_EVENTUALLY),
                file.stream().map(Query::kind).toList());
        assertEquals(List.of(2, 4, 5), file.stream().map(Query::line).toList());
        assertEquals(Outcome.SATISFIED, new Verifier(n, VerifierOptions.defaults()).verify(file.get(0)).outcome());
        QueryException fileLine = assertThrows(QueryException.class,
                () -> new Verifier(n, VerifierOptions.defaults()).verify(file.get(1)));
        assertTrue(fileLine.getMessage().startsWith("line 4: query 'oops', column 1: not a query"),
                fileLine.getMessage());
        QueryException fileName = assertThrows(QueryException.class,
                () -> new Verifier(n, VerifierOptions.defaults()).verify(file.get(2)));
        assertEquals("line 5: query 'E<> P(1).cs and foo > 1', column 17: unknown name 'foo'", fileName.getMessage());
        assertEquals(2, Query.parseFile("E<> a\n/* x\n y */ A[] b // c\n").size());
        assertFalse(Query.parseFile("").iterator().hasNext());
    }
}
