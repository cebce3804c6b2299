package io.dtron.engine.internal.eval;

import static io.dtron.engine.internal.zone.Bound.le;
import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Edge;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.Process;
import java.nio.file.Path;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

/**
 * The real guards and updates of Uppaal's train-gate example: the Gate keeps a queue of train ids with its
 * functions enqueue, dequeue, front and tail.
 */
class TrainGateTest {
    private Network network;
    private Evaluator evaluator;
    private int[] vars;
    private Process gate;
    private final ClockResets resets = new ClockResets();

    @BeforeEach
    void load() throws Exception {
        String shared = System.getProperty("dtron.shared", "../../shared");
        network = ModelLoader.load(Path.of(shared, "models", "uppaal-examples", "train-gate.xml"));
        evaluator = new Evaluator(network);
        vars = network.initialState();
        gate = network.process("Gate").orElseThrow();
    }

    /** The Gate's edge from {@code source} to {@code target} with (or without) a guard on {@code len}. */
    private Edge gateEdge(String source, String target, String guardText) {
        int s = gate.locations().indexOf(location(source));
        int t = gate.locations().indexOf(location(target));
        return gate.edges().stream()
                .filter(e -> e.source() == s && e.target() == t)
                .filter(e -> guardText == null ? e.guard() == null || !e.guard().pos().text().contains("len")
                        : e.guard() != null && e.guard().pos().text().equals(guardText))
                .findFirst().orElseThrow();
    }

    private io.dtron.model.Location location(String name) {
        return name == null ? gate.locations().stream().filter(l -> l.name().startsWith("_")).findFirst()
                .orElseThrow() : gate.location(name);
    }

    private int[] queue() {
        int offset = network.variable("Gate.list").orElseThrow().offset();
        int len = vars[network.variable("Gate.len").orElseThrow().offset()];
        int[] q = new int[len];
        System.arraycopy(vars, offset, q, 0, len);
        return q;
    }

    private boolean guard(Edge e, int... frame) {
        return evaluator.dataHolds(e.guard(), vars, frame);
    }

    private void run(Edge e, int... frame) {
        for (var u : e.updates()) {
            evaluator.execute(u, vars, frame, resets);
        }
    }

    private String channel(Edge e, int... frame) {
        return network.channelName(evaluator.channel(e.sync().channel(), vars, frame));
    }

    @Test
    void theQueueFollowsArrivalsAndDepartures() {
        Edge firstArrival = gateEdge("Free", "Occ", "len == 0");
        Edge restart = gateEdge("Free", "Occ", "len > 0");
        Edge arrival = gateEdge("Occ", null, null);
        Edge stop = gateEdge(null, "Occ", null);
        Edge leave = gateEdge("Occ", "Free", "e == front()");

        assertTrue(guard(firstArrival, 2));
        assertFalse(guard(restart));
        assertEquals("appr[2]", channel(firstArrival, 2));
        run(firstArrival, 2);
        assertArrayEquals(new int[] {2}, queue());
        assertFalse(guard(firstArrival, 0));

        run(arrival, 5);
        assertEquals("stop[5]", channel(stop));
        run(arrival, 0);
        assertEquals("stop[0]", channel(stop));
        assertArrayEquals(new int[] {2, 5, 0}, queue());

        assertTrue(guard(leave, 2));
        assertFalse(guard(leave, 5));
        assertEquals("leave[2]", channel(leave, 2));
        run(leave, 2);
        assertArrayEquals(new int[] {5, 0}, queue());
        assertEquals(0, vars[network.variable("Gate.list").orElseThrow().offset() + 2], "dequeue clears the slot");

        assertTrue(guard(restart));
        assertEquals("go[5]", channel(restart));
        run(leave, 5);
        run(leave, 0);
        assertArrayEquals(new int[0], queue());
        assertFalse(guard(restart));
        assertEquals(0, resets.size(), "the Gate has no clocks");
    }

    @Test
    void queueErrorsAreReportedWithTheModelsNames() {
        Edge arrival = gateEdge("Occ", null, null);
        Edge stop = gateEdge(null, "Occ", null);
        Edge leave = gateEdge("Occ", "Free", "e == front()");
        ModelRuntimeException e = assertThrows(ModelRuntimeException.class, () -> channel(stop));
        assertEquals("index -1 is out of range [0,6] of 'list'", e.getMessage());
        e = assertThrows(ModelRuntimeException.class, () -> run(leave, 0));
        assertEquals("the value -1 is outside int[0,6] of 'Gate.len'", e.getMessage());
        for (int id = 0; id < 6; id++) {
            run(arrival, id);
        }
        assertArrayEquals(new int[] {0, 1, 2, 3, 4, 5}, queue());
        e = assertThrows(ModelRuntimeException.class, () -> run(arrival, 3));
        assertEquals("the value 7 is outside int[0,6] of 'Gate.len'", e.getMessage());
    }

    @Test
    void trainsResetTheirOwnClockAndRespectTheirInvariants() {
        Process train = network.process("Train(3)").orElseThrow();
        int x = network.clock("Train(3).x").orElseThrow().index();
        int safe = train.locations().indexOf(train.location("Safe"));
        int appr = train.locations().indexOf(train.location("Appr"));
        int cross = train.locations().indexOf(train.location("Cross"));
        Edge approach = train.edges().stream().filter(e -> e.source() == safe).findFirst().orElseThrow();
        Edge enter = train.edges().stream().filter(e -> e.source() == appr && e.target() == cross)
                .findFirst().orElseThrow();
        assertEquals("appr[3]", channel(approach));
        run(approach);
        assertEquals(1, resets.size());
        assertEquals(x, resets.clock(0));
        assertEquals(0, resets.value(0));

        int dimension = network.clockCount() + 1;
        Dbm zone = Dbm.unconstrained(dimension);
        assertTrue(evaluator.constrain(train.location("Appr").invariant(), vars, null, zone, 1000));
        assertTrue(evaluator.constrain(enter.guard(), vars, null, zone, 1000));
        Dbm expected = Dbm.unconstrained(dimension);
        expected.constrain(x, 0, le(20_000));
        expected.constrain(0, x, le(-10_000));
        assertEquals(expected, zone);
    }
}
