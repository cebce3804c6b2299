package io.dtron.engine.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.verify.VerificationResult.Outcome;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.math.BigDecimal;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * Uppaal's demo models from {@code ../shared/models/uppaal-examples}. None of these four files carries
 * {@code <queries>}, so the queries are the classic ones for each model, and each answer was worked out by hand
 * from the model (the reason is next to it).
 */
class UppaalExamplesTest {
    static final Path EXAMPLES = Path.of(System.getProperty("dtron.shared", "../../shared"), "models",
            "uppaal-examples");

    static Network example(String file) throws Exception {
        return ModelLoader.load(EXAMPLES.resolve(file));
    }

    private static Outcome answer(Network n, String query) {
        return new Verifier(n, VerifierOptions.defaults()).verify(Query.parse(query)).outcome();
    }

    @Test
    void trainGate() throws Exception {
        Network n = example("train-gate.xml");
        assertTrue(n.queries().isEmpty(), "the file has no queries of its own");
        // the gate is Occ as soon as one train approaches
        assertEquals(Outcome.SATISFIED, answer(n, "E<> Gate.Occ"));
        // train 0 approaches first and crosses (x >= 10), train 1 approaches later and is stopped (x <= 10)
        assertEquals(Outcome.SATISFIED, answer(n, "E<> Train(0).Cross and Train(1).Stop"));
        // only the train at the front of the queue is let go, and it leaves (leave[front()]) before the next is
        // let go: never two trains on the crossing
        assertEquals(Outcome.SATISFIED, answer(n,
                "A[] forall (i : id_t) forall (j : id_t) Train(i).Cross && Train(j).Cross imply i == j"));
        // at most N trains are queued, so list[N], the (N+1)-th slot, is never written
        assertEquals(Outcome.SATISFIED, answer(n, "A[] Gate.list[N] == 0"));
        // a queued train is let go (go is urgent) once the train in front leaves, within x <= 5 of crossing
        assertEquals(Outcome.SATISFIED, answer(n, "Train(0).Appr --> Train(0).Cross"));
        // a crossing train must leave by x <= 5, and a stopped one gets its go: some move is always possible
        assertEquals(Outcome.SATISFIED, answer(n, "A[] not deadlock"));
        // the gate's queue is full with all six trains waiting or crossing
        assertEquals(Outcome.SATISFIED, answer(n, "E<> Gate.len == N"));
    }

    @Test
    void bridgeTheFourVikingsCrossInSixtyMinutesAndNoLess() throws Exception {
        Network n = example("bridge.xml");
        String allSafe = "Viking1.safe and Viking2.safe and Viking3.safe and Viking4.safe";
        // 5 and 10 cross (10), 5 returns (5), 20 and 25 cross (25), 10 returns (10), 5 and 10 cross (10): 60
        VerificationResult sixty = new Verifier(n, VerifierOptions.defaults())
                .verify(Query.parse("E<> " + allSafe + " and time <= 60"));
        assertEquals(Outcome.SATISFIED, sixty.outcome());
        Trace t = sixty.trace();
        assertNotNull(t);
        assertEquals(0, t.concrete().get(t.concrete().size() - 1).time().compareTo(BigDecimal.valueOf(60)),
                t.toText());
        // any other schedule takes longer: sending 25 back, or 5 with each of the others, costs more than 60
        assertEquals(Outcome.VIOLATED, answer(n, "E<> " + allSafe + " and time < 60"));
        // the torch is on one side (L) only; only two may carry it at once
        assertEquals(Outcome.SATISFIED, answer(n, "A[] not (Torch.one and Torch.two)"));
    }

    @Test
    void twoDoorsAreNeverOpenAtOnce() throws Exception {
        Network n = example("2doors.xml");
        // a door opens only after receiving closed2 from the other door, which it sends only when idle or
        // closed; both users can push, and each door can open
        assertEquals(Outcome.SATISFIED, answer(n, "A[] not (Door1.open and Door2.open)"));
        assertEquals(Outcome.SATISFIED, answer(n, "E<> Door1.open"));
        assertEquals(Outcome.SATISFIED, answer(n, "E<> Door2.open"));
        // the invariant of open is x <= 8
        assertEquals(Outcome.SATISFIED, answer(n, "A[] Door1.open imply Door1.x <= 8"));
        assertEquals(Outcome.VIOLATED, answer(n, "E<> Door1.open and Door1.x > 8"));
        // opening has x <= 6 and its edge x == 6 to open
        assertEquals(Outcome.SATISFIED, answer(n, "Door1.opening --> Door1.open"));
    }

    @Test
    void fischerWithSixProcesses() throws Exception {
        Network n = example("fischer.xml");
        // req is left within k and wait is left for cs only after more than k: the classic constants
        assertEquals(Outcome.SATISFIED, answer(n,
                "A[] forall (i : id_t) forall (j : id_t) P(i).cs && P(j).cs imply i == j"));
        assertEquals(Outcome.SATISFIED, answer(n, "E<> P(1).cs"));
        // req has the invariant x <= k and one way out
        assertEquals(Outcome.SATISFIED, answer(n, "P(1).req --> P(1).wait"));
    }

    @Test
    void theBenchmarksOwnQueriesAreRead() throws Exception {
        Network n = ModelLoader.load(EXAMPLES.resolveSibling("benchmarks").resolve("fischer-4.xml"));
        Verifier v = new Verifier(n, VerifierOptions.defaults());
        List<Query> queries = v.modelQueries();
        assertEquals(2, queries.size());
        assertEquals("A[] forall (i : pid_t) forall (j : pid_t) i != j imply not (P(i).cs and P(j).cs)",
                queries.get(0).text());
        VerificationResult mutex = v.verify(queries.get(0));
        assertEquals(Outcome.SATISFIED, mutex.outcome());
        // the figures of TChecker's covreach on the same model (benchmarks/README.md): 268 visited, 220 stored
        assertEquals(268, mutex.statistics().explored());
        assertEquals(220, mutex.statistics().stored());
        assertEquals(Outcome.SATISFIED, v.verify(queries.get(1)).outcome(), "A[] !deadlock");
    }
}
