package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import org.junit.jupiter.api.Test;

/** The network that loading produces: layout, folding, expression types, instantiation, interfaces. */
class NetworkTest {

    private static Network load(String text) throws ModelException {
        return ModelLoader.load("test.xta", text);
    }

    @Test
    void variablesAreLaidOutInOneStateVectorWithTheirInitialValues() throws ModelException {
        Network n = load("""
                const int N = 3;
                typedef struct { int[0,5] a; bool b; } pair_t;
                int x = 2;
                int[1,4] r;
                pair_t p = { 4, true };
                int arr[N] = { 7, 8, 9 };
                process P() { int local = N * 2; state A; init A; }
                system P;
                """);
        assertEquals(List.of("x", "r", "p", "arr", "P.local"), n.variables().stream().map(Variable::name).toList());
        assertEquals(1 + 1 + 2 + 3 + 1, n.stateSize());
        // r's range excludes 0, so it starts at its lower bound
        assertArrayEquals(new int[] {2, 1, 4, 1, 7, 8, 9, 6}, n.initialState());
        assertEquals(4, n.variable("arr").orElseThrow().offset());
        assertEquals("P", n.variable("P.local").orElseThrow().owner());
    }

    @Test
    void constantsAreFoldedAndGuardsAreTypedAsClockConstraints() throws ModelException {
        Network n = load("""
                const int K = 2 * 3 + 1;
                clock x, y;
                int v;
                process P() {
                    state A { x <= K }, B;
                    init A;
                    trans A -> B { guard x >= K - 2 && v == 1 && x - y == 3; assign x = 0, v = K; };
                }
                system P;
                """);
        Process p = n.processes().get(0);
        Expression invariant = p.locations().get(0).invariant();
        assertEquals(new Type.ClockConstraint(Type.ConstraintKind.INVARIANT), invariant.type());
        Expression.Binary bound = (Expression.Binary) invariant;
        assertEquals(7, ((Expression.Constant) bound.right()).value());
        Edge edge = p.edges().get(0);
        // as in Uppaal: bounds are invariant-like, '==' on clocks makes a guard
        assertEquals(new Type.ClockConstraint(Type.ConstraintKind.GUARD), edge.guard().type());
        Expression.Assign reset = (Expression.Assign) edge.updates().get(0);
        assertInstanceOf(Expression.ClockRef.class, reset.target());
        Expression.Assign setV = (Expression.Assign) edge.updates().get(1);
        assertEquals(7, ((Expression.Constant) setV.value()).value());
        assertNull(edge.sync());
    }

    @Test
    void clockOffsetsAndDisjunctionsWithDataAreGuardsAsInUppaal() throws ModelException {
        Network n = load("""
                clock x, y;
                bool b;
                process P() {
                    state A { x + 1 <= 5 && (b || y - 2 >= x) }; init A;
                    trans A -> A { guard b || x + 1 < 3; }, A -> A { guard 2 + x == y; };
                }
                system P;
                """);
        Process p = n.processes().get(0);
        assertEquals(new Type.ClockConstraint(Type.ConstraintKind.INVARIANT), p.locations().get(0).invariant().type());
        assertEquals(new Type.ClockConstraint(Type.ConstraintKind.INVARIANT), p.edges().get(0).guard().type());
        Expression.Binary eq = (Expression.Binary) p.edges().get(1).guard();
        assertEquals(Type.Clock.INSTANCE, eq.left().type(), "2 + x is a clock offset by an integer");
        assertEquals(new Type.ClockConstraint(Type.ConstraintKind.GUARD), eq.type());
    }

    @Test
    void selectBindingsAndQuantifiersTakeFrameSlots() throws ModelException {
        Network n = load("""
                typedef int[0,2] id_t;
                chan c[id_t];
                bool busy[id_t];
                process P() {
                    state A; init A;
                    trans A -> A { select i : id_t, j : id_t; guard forall (k : id_t) !busy[k]; sync c[i]!; assign busy[j] = true; };
                }
                process Q() { state A; init A; trans A -> A { select i : id_t; sync c[i]?; }; }
                system P, Q;
                """);
        Edge e = n.processes().get(0).edges().get(0);
        assertEquals(List.of("i", "j"), e.selects().stream().map(Edge.Select::name).toList());
        assertEquals(0, e.selects().get(0).lower());
        assertEquals(2, e.selects().get(0).upper());
        assertEquals(3, e.frameSize());
        assertInstanceOf(Expression.Quantified.class, e.guard());
        assertEquals(Edge.Direction.SEND, e.sync().direction());
        assertEquals("c[2]", n.channelName(2));
    }

    @Test
    void functionsAreCompiledWithTheirFramesAndSideEffects() throws ModelException {
        Network n = load("""
                int q[4];
                int len;
                int front() { return q[0]; }
                void push(int v) { q[len] = v; len++; }
                int total() { int s = 0; for (i : int[0,3]) { s += q[i]; } return s; }
                process P() { state A; init A; trans A -> A { guard front() == 0 && total() < 10; assign push(1); }; }
                system P;
                """);
        Function front = n.functions().get(0);
        Function push = n.functions().get(1);
        Function total = n.functions().get(2);
        assertTrue(front.sideEffectFree());
        assertTrue(!push.sideEffectFree());
        assertTrue(total.sideEffectFree());
        assertEquals(2, total.frameSize());
        assertEquals("push", ((Expression.Call) n.processes().get(0).edges().get(0).updates().get(0)).name());
    }

    @Test
    void aFunctionWithSideEffectsCannotGuardAnEdge() {
        ModelException e = assertThrows(ModelException.class, () -> load("""
                int len;
                int pop() { len--; return len; }
                process P() { state A; init A; trans A -> A { guard pop() > 0; }; }
                system P;
                """));
        assertEquals("a guard must not have side effects", e.errors().get(0).message());
        assertEquals(3, e.errors().get(0).line());
    }

    @Test
    void referenceParametersBindToTheArgumentsVariables() throws ModelException {
        Network n = load("""
                int a, b;
                clock x;
                process P(int &v, clock &c, const int k) { state A; init A; trans A -> A { guard c > k; assign v = k, c = 0; }; }
                P1 = P(a, x, 1);
                P2 = P(b, x, 2);
                system P1, P2;
                """);
        Expression.Assign first = (Expression.Assign) n.processes().get(0).edges().get(0).updates().get(0);
        Expression.Assign second = (Expression.Assign) n.processes().get(1).edges().get(0).updates().get(0);
        assertEquals("a", ((Expression.VariableRef) first.target()).variable().name());
        assertEquals("b", ((Expression.VariableRef) second.target()).variable().name());
        assertEquals(2, ((Expression.Constant) second.value()).value());
        assertEquals(1, n.clockCount());
    }

    @Test
    void systemLinePrioritiesAndChannelPriorities() throws ModelException {
        Network n = load("""
                chan a, b, c;
                chan priority a, b < default < c;
                process P() { state A; init A; }
                process Q() { state A; init A; }
                system P < Q;
                """);
        assertEquals(0, n.processes().get(0).priority());
        assertEquals(1, n.processes().get(1).priority());
        assertEquals(List.of(0, 0, 2), n.channelPriority());
    }

    @Test
    void committedAndUrgentLocations() throws ModelException {
        Network n = load("""
                process P() { state A, B, C; commit B; urgent C; init A; trans A -> B {}, -> C {}, C -> A {}; }
                system P;
                """);
        List<Location> l = n.processes().get(0).locations();
        assertEquals(List.of(Location.Kind.NORMAL, Location.Kind.COMMITTED, Location.Kind.URGENT),
                l.stream().map(Location::kind).toList());
        List<Edge> e = n.processes().get(0).edges();
        // "-> C" continues from the previous edge's target
        assertEquals(1, e.get(1).source());
        assertEquals(2, e.get(1).target());
    }

    @Test
    void interfaceFromNamesAttachesVariablesByPrefix() throws ModelException {
        Network n = load("""
                chan i_move, o_done, internal;
                int i_move_amount, i_move_speed, o_done_status, unrelated;
                process P() { state A; init A; trans A -> A { sync i_move?; }, A -> A { sync o_done!; }; }
                system P;
                """);
        TestInterface i = TestInterface.fromNames(n);
        assertEquals(List.of("move"), i.inputs().stream().map(TestInterface.ObservableChannel::name).toList());
        assertEquals(List.of("amount", "speed"),
                i.input("move").orElseThrow().variables().stream().map(TestInterface.AttachedVariable::name).toList());
        assertEquals("o_done_status", i.output("done").orElseThrow().variables().get(0).variable().name());
        assertEquals("i_move", i.input("move").orElseThrow().modelName());
    }

    @Test
    void modelsLoadFromTheClasspathAndFromTheStore() throws ModelException {
        Network fromResource = ModelLoader.loadResource(getClass().getClassLoader(), "io/dtron/model/counter.xta");
        assertEquals("Counter", fromResource.processes().get(0).name());
        ModelStore store = new ModelStore();
        store.put("m", "chan c; process P() { state A; init A; } system P;");
        assertEquals(1, ModelLoader.load(store, "m").channelCount());
        store.put("m", "chan c, d; process P() { state A; init A; } system P;");
        assertEquals(2, ModelLoader.load(store, "m").channelCount(), "a replaced model reloads");
        ModelException missing = assertThrows(ModelException.class, () -> ModelLoader.load(store, "other"));
        assertTrue(missing.getMessage().contains("no model of that name"));
        assertThrows(ModelException.class, () -> ModelLoader.loadResource(getClass().getClassLoader(), "nope.xml"));
    }

    @Test
    void aMissingFileIsAModelErrorNotAnException() {
        ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load(java.nio.file.Path.of("no/such.xml")));
        assertEquals("no/such.xml: error: no such file", e.errors().get(0).format());
    }
}
