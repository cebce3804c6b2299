package io.dtron.engine.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.util.List;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;

/**
 * A query's errors about names say what the name is and what was probably meant, at the column of the name: a
 * misspelt process, location or variable with the nearest names, a process or template used as a value, and
 * implication written {@code ->} or {@code implies}.
 */
class QueryErrorsTest {
    /** A train and a gate, and three cars of one template (Car(0), Car(1), Car(2)). */
    private static final String MODEL = """
            typedef int[0,2] id_t;
            chan appr, leave;
            int[0,1] count = 0;
            process Train() {
                clock x;
                state Far, Appr { x <= 5 }, Cross { x <= 5 };
                init Far;
                trans Far -> Appr { sync appr!; assign x = 0, count = 1; },
                      Appr -> Cross { guard x >= 3; },
                      Cross -> Far { guard x >= 3; sync leave!; };
            }
            process Gate() {
                int len = 0;
                state Open, Closed;
                init Open;
                trans Open -> Closed { sync appr?; assign len = 1; },
                      Closed -> Open { sync leave?; assign len = 0; };
            }
            process Car(const id_t id) {
                state Idle, Run;
                init Idle;
                trans Idle -> Run { }, Run -> Idle { };
            }
            system Train, Gate, Car;
            """;

    private static Network network;

    @BeforeAll
    static void load() throws Exception {
        network = ModelLoader.load("crossing.xta", MODEL);
    }

    private static String error(String query) {
        return assertThrows(QueryException.class,
                () -> new Verifier(network, VerifierOptions.defaults()).verify(Query.parse(query)), query).getMessage();
    }

    @Test
    void aMisspeltProcessIsUnknownWithTheNearestNames() {
        assertEquals("query 'E<> Trian.Cross', column 5: unknown process 'Trian' (did you mean 'Train'?)",
                error("E<> Trian.Cross"));
        assertEquals("query 'E<> Train.x > 3 && Gat.len == 1', column 20: unknown process 'Gat' (did you mean"
                + " 'Gate'?)", error("E<> Train.x > 3 && Gat.len == 1"));
        assertEquals("query 'E<> Cra(1).Run', column 5: unknown process 'Cra(1)' (did you mean 'Car(1)'?)",
                error("E<> Cra(1).Run"));
        assertEquals("query 'E<> Car(5).Run', column 5: unknown process 'Car(5)': the processes of template Car are"
                + " Car(0), Car(1), Car(2)", error("E<> Car(5).Run"));
        assertEquals("query 'E<> Bridge.Up', column 5: unknown process 'Bridge'", error("E<> Bridge.Up"));
    }

    @Test
    void anUnknownLocationOrVariableOfAProcessIsNamedAtItsColumn() {
        assertEquals("query 'E<> Train.Crss', column 11: process Train has no location 'Crss' (did you mean"
                + " 'Cross'?)", error("E<> Train.Crss"));
        assertEquals("query 'E<> Gate.lenn > 0', column 10: process Gate has no variable 'lenn' (did you mean"
                + " 'len'?)", error("E<> Gate.lenn > 0"));
        assertEquals("query 'E<> Train.xx > 1', column 11: process Train has no clock 'xx' (did you mean 'x'?)",
                error("E<> Train.xx > 1"));
        assertEquals("query 'E<> Car(2).Running', column 12: process Car(2) has no location or variable 'Running'",
                error("E<> Car(2).Running"));
        // the second property of a leads-to query: its column counts from the start of the query
        assertEquals("query 'Gate.Open --> Gate.Ope', column 20: process Gate has no location 'Ope' (did you mean"
                + " 'Open'?)", error("Gate.Open --> Gate.Ope"));
    }

    @Test
    void anUnknownNameGetsTheNearestGlobalOrTheProcessesItBelongsTo() {
        assertEquals("query 'E<> cont > 0', column 5: unknown name 'cont' (did you mean 'count'?)",
                error("E<> cont > 0"));
        assertEquals("query 'E<> Gate.Open && len == 1', column 18: unknown name 'len' (did you mean 'Gate.len'?)",
                error("E<> Gate.Open && len == 1"));
        assertEquals("query 'E<> y > 1', column 5: unknown name 'y'", error("E<> y > 1"));
    }

    @Test
    void aProcessOrTemplateUsedAsAValueSaysHowToTestALocation() {
        assertEquals("query 'E<> Train == Cross', column 5: 'Train' is a process, not a value: Train.Cross tests"
                + " whether it is in location Cross", error("E<> Train == Cross"));
        assertEquals("query 'E<> Cross != Train', column 14: 'Train' is a process, not a value: Train.Cross tests"
                + " whether it is in location Cross", error("E<> Cross != Train"));
        assertEquals("query 'E<> Train.x + Gate > 1', column 15: 'Gate' is a process, not a value: Gate.Open tests"
                + " whether it is in location Open", error("E<> Train.x + Gate > 1"));
        assertEquals("query 'A[] Gate', column 5: 'Gate' is a process, not a value: Gate.Open tests whether it is in"
                + " location Open", error("A[] Gate"));
        assertEquals("query 'E<> Car(1) == Run', column 5: 'Car(1)' is a process, not a value: Car(1).Run tests"
                + " whether it is in location Run", error("E<> Car(1) == Run"));
        assertEquals("query 'E<> Car == 1', column 5: 'Car' is a template, not a value: a query tests the location"
                + " of one of its processes, as Car(0).Idle", error("E<> Car == 1"));
        assertEquals("query 'E<> Car.Run', column 5: 'Car' is a template, not a process: name one of its processes,"
                + " as Car(0).Run", error("E<> Car.Run"));
    }

    @Test
    void implicationWrittenAsOtherLogicsWriteItIsAnErrorAtItsPlaceThatSuggestsImply() {
        assertEquals("query 'E<> Train.Cross -> Gate.Closed', column 17: '->' is not an operator of queries:"
                + " implication is written imply, as in p imply q", error("E<> Train.Cross -> Gate.Closed"));
        assertEquals("query 'A[] (Train.Cross implies Gate.Closed)', column 18: 'implies' is not an operator of"
                + " queries: implication is written imply, as in p imply q",
                error("A[] (Train.Cross implies Gate.Closed)"));
        assertEquals("query 'Gate.Closed --> Train.Far -> Gate.Open', column 27: '->' is not an operator of queries:"
                + " implication is written imply, as in p imply q", error("Gate.Closed --> Train.Far -> Gate.Open"));
        // without a path quantifier, p -> q may have meant leads-to too
        QueryException bare = assertThrows(QueryException.class, () -> Query.parse("Train.Cross -> Gate.Closed"));
        assertEquals("query 'Train.Cross -> Gate.Closed', column 13: '->' is not an operator of queries: implication"
                + " is written imply (A[] p imply q), and a leads-to query p --> q", bare.getMessage());
        QueryException implies = assertThrows(QueryException.class, () -> Query.parse("Train.Cross implies Gate.Open"));
        assertEquals("query 'Train.Cross implies Gate.Open', column 13: 'implies' is not an operator of queries:"
                + " implication is written imply (A[] p imply q), and a leads-to query p --> q", implies.getMessage());
        // imply itself, and --> for leads-to, are what they should be
        assertEquals(VerificationResult.Outcome.SATISFIED, new Verifier(network, VerifierOptions.defaults())
                .verify(Query.parse("A[] Train.Cross imply Gate.Closed")).outcome());
        assertEquals(Query.Kind.LEADS_TO, Query.parse("Train.Appr-->Train.Cross").kind());
    }

    @Test
    void inAQueryFileTheErrorsKeepTheirLines() {
        List<Query> file = Query.parseFile("""
                // two mistakes
                E<> Trian.Cross
                Train.Cross -> Gate.Closed
                """);
        assertEquals("line 2: query 'E<> Trian.Cross', column 5: unknown process 'Trian' (did you mean 'Train'?)",
                assertThrows(QueryException.class, () -> new Verifier(network, VerifierOptions.defaults())
                        .verify(file.get(0))).getMessage());
        assertEquals("line 3: query 'Train.Cross -> Gate.Closed', column 13: '->' is not an operator of queries:"
                + " implication is written imply (A[] p imply q), and a leads-to query p --> q",
                file.get(1).reason());
    }
}
