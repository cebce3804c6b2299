package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.ast.Query;
import java.util.List;
import java.util.Map;
import java.util.stream.Collectors;
import org.junit.jupiter.api.Test;

/**
 * Constructs that Uppaal accepts and that once stopped real models from loading: the whole query language,
 * Gantt charts, constants beyond 16 bits, functions evaluated in constants, clock rates, channel priorities
 * between named channels, channel kinds of reference parameters, {@code **}, out-of-range constant indices and
 * the constructs of statistical model checking, which load but cannot run. Every model here was written for
 * this test; positions were counted by hand.
 */
class UppaalFidelityTest {
    private static final String XTA = "m.xta";
    private static final String XML = "m.xml";

    private static Network load(String text) throws ModelException {
        return ModelLoader.load(XTA, text);
    }

    private static Network resource(String name) throws ModelException {
        return ModelLoader.loadResource(UppaalFidelityTest.class.getClassLoader(), "io/dtron/model/fidelity/" + name);
    }

    private static int initial(Network n, String variable) {
        return n.variable(variable).orElseThrow().initial()[0];
    }

    // ================================================================ queries and gantt charts

    @Test
    void everyKindOfQueryParsesAndABadQueryIsAnErrorOfItsOwn() throws ModelException {
        Network n = resource("queries.xml");
        assertEquals(2, n.processes().size(), "the gantt block of the system section is accepted");
        assertEquals(List.of(Query.Kind.EXISTS_EVENTUALLY, Query.Kind.ALWAYS_GLOBALLY, Query.Kind.LEADS_TO,
                Query.Kind.VALUE_BOUNDS, Query.Kind.VALUE_BOUNDS, Query.Kind.VALUE_BOUNDS, Query.Kind.SIMULATE,
                Query.Kind.SIMULATE, Query.Kind.PROBABILITY, Query.Kind.PROBABILITY, Query.Kind.PROBABILITY,
                Query.Kind.EXPECTATION, Query.Kind.STRATEGY, Query.Kind.ALWAYS_GLOBALLY, Query.Kind.STRATEGY,
                Query.Kind.STRATEGY_FILE, Query.Kind.SCENARIO, Query.Kind.INVALID),
                n.queries().stream().map(Query::kind).toList());
        Query first = n.queries().get(0);
        assertEquals("E<> P.B", first.text());
        assertEquals("reachable", first.comment());
        assertEquals(24, first.pos().line());
        assertTrue(first.isValid());
        assertEquals("Fast", n.queries().get(13).strategy());
        Query bad = n.queries().get(17);
        assertFalse(bad.isValid());
        assertEquals("E<> P.B and (", bad.text());
        Diagnostic error = bad.errors().get(0);
        assertEquals(41, error.line());
        assertEquals(38, error.column());
        assertTrue(error.message().startsWith("syntax error: unexpected end of text"), error::format);
        assertTrue(n.warnings().isEmpty(), () -> "a query's errors are not the model's: " + n.warnings());
    }

    @Test
    void aBadQueryHidesNoErrorOfTheModel() {
        ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load(XML, """
                <nta><declaration>int n;</declaration>
                <template><name>P</name><location id="a"><name>A</name></location><init ref="a"/>
                <transition><source ref="a"/><target ref="a"/><label kind="guard">m &gt; 1</label></transition>
                </template>
                <system>system P;</system>
                <queries><query><formula>Pr[&lt;=10](&lt;&gt; P.A) &gt;=</formula></query></queries>
                </nta>
                """));
        assertEquals(1, e.errors().size(), e::getMessage);
        assertEquals("unknown name 'm'", e.errors().get(0).message());
    }

    @Test
    void anEmptyExpectationNameIsRejectedInTheQueryOnly() throws ModelException {
        Network n = ModelLoader.load(XML, """
                <nta><template><name>P</name><location id="a"><name>A</name></location><init ref="a"/></template>
                <system>system P;</system>
                <queries><query><formula>F[&lt;=10](max: 1)</formula></query>
                <query><formula>E[&lt;=10](avg: 1)</formula></query></queries>
                </nta>
                """);
        assertEquals(List.of(Query.Kind.INVALID, Query.Kind.INVALID), n.queries().stream().map(Query::kind).toList());
        assertTrue(n.queries().get(0).errors().get(0).message().contains("expected 'E'"));
        assertTrue(n.queries().get(1).errors().get(0).message().contains("'min' or 'max', not 'avg'"));
    }

    @Test
    void aGanttBlockInAnXtaFileIsAccepted() throws ModelException {
        Network n = load("""
                int[0,3] k;
                process P() { state A, B; init A; trans A -> B { assign k = 2; }; }
                system P;
                gantt { Busy: P.B -> 1, k > 1 -> 2; }
                """);
        assertEquals(1, n.processes().size());
    }

    // ================================================================ constants

    @Test
    void constantsAndConstParametersTakeAny32BitValue() throws ModelException {
        Network n = load("""
                const int CYCLES = 2147483647;
                const int LOW = -2147483647 - 1;
                const int PERIODS[2] = {100000, -70000};
                int[0, CYCLES] c = CYCLES;
                int[LOW, 0] p = PERIODS[1];
                process P(const int limit) { int[LOW, limit] v = limit; state A; init A; }
                P1 = P(100000);
                system P1;
                """);
        assertEquals(new Type.Int(0, Integer.MAX_VALUE), n.variable("c").orElseThrow().type());
        assertEquals(Integer.MAX_VALUE, initial(n, "c"));
        assertEquals(100000, initial(n, "P1.v"));
        assertEquals(-70000, initial(n, "p"));
        ModelException e = assertThrows(ModelException.class, () -> load("""
                int big = 100000;
                process P() { state A; init A; }
                system P;
                """));
        assertTrue(e.errors().get(0).message().contains("outside its range int"), e::getMessage);
    }

    @Test
    void pureFunctionsAreEvaluatedInConstants() throws ModelException {
        Network n = load("""
                int def_prio(int p) { return p * 2 + 1; }
                int sum_to(int k) { int s = 0; int i; for (i = 1; i <= k; i++) { s += i; } return s; }
                int pick(const int t[3], int i) { if (i < 0) return -1; return t[i]; }
                const int TABLE[3] = {4, 5, 6};
                const int P = def_prio(13);
                const int S = sum_to(10) + pick(TABLE, 2);
                typedef int[0, def_prio(2)] small_t;
                small_t k = P - 22;
                int[0, S] s = S;
                process Q(const int a) { int[0, 99] v = a; state A; init A; }
                Q1 = Q(def_prio(4));
                system Q1;
                """);
        assertEquals(5, initial(n, "k"));
        assertEquals(new Type.Int(0, 5), n.variable("k").orElseThrow().type());
        assertEquals(61, initial(n, "s"));
        assertEquals(9, initial(n, "Q1.v"));
    }

    @Test
    void aFunctionThatReadsAVariableIsNotAConstant() {
        ModelException e = assertThrows(ModelException.class, () -> load("""
                int g = 3;
                int read() { return g; }
                const int C = read();
                process P() { state A; init A; }
                system P;
                """));
        assertEquals(1, e.errors().size(), e::getMessage);
        Diagnostic d = e.errors().get(0);
        assertTrue(d.message().contains("the initial value of 'C' must be computable at compile time"), d::format);
        assertEquals(3, d.line());
    }

    @Test
    void powerOperator() throws ModelException {
        Network n = load("""
                const int K = 2 ** 10;
                const int R = 3 ** 2 ** 2;
                int[0, K] k = K;
                int r = R;
                int v = 3;
                process P() { state A; init A; trans A -> A { assign v = v ** 2; }; }
                system P;
                """);
        assertEquals(1024, initial(n, "k"));
        assertEquals(81, initial(n, "r"), "** is right-associative");
        Edge e = n.processes().get(0).edges().get(0);
        Expression.Assign a = (Expression.Assign) e.updates().get(0);
        assertEquals(Expression.Operator.POW, ((Expression.Binary) a.value()).op());
    }

    @Test
    void anOutOfRangeConstantIndexIsAnErrorOnlyWhenEvaluated() throws ModelException {
        Network n = load("""
                const int N = 3;
                int a[N];
                bool b[N];
                void f() { a[N] = 1; }
                process P() { state S { a[3] <= 2 }; init S; trans S -> S { guard b[N]; assign a[N] = 1, f(); }; }
                system P;
                """);
        assertEquals(4, n.warnings().size(), () -> n.warnings().toString());
        assertTrue(n.warnings().stream().allMatch(w -> w.message().contains("index 3 is out of range [0,2]")));
        assertTrue(n.startErrors().isEmpty(), "the model may run until it evaluates the index");
    }

    // ================================================================ clocks, channels, priorities

    @Test
    void clockRatesInInvariants() throws ModelException {
        Network n = load("""
                clock x, y[3];
                const int K = 2;
                process P() {
                state Stopped { x' == 0 && x <= 5 }, Scaled { x' == K * 2 }, All { forall (i : int[0,2]) y[i]' == 0 };
                init Stopped;
                trans Stopped -> Scaled {}, Scaled -> All {};
                }
                system P;
                """);
        List<Location> locations = n.processes().get(0).locations();
        assertEquals(Type.ConstraintKind.INVARIANT, ((Type.ClockConstraint) locations.get(0).invariant().type()).kind());
        assertTrue(locations.get(1).invariant() instanceof Expression.ClockRate);
        assertTrue(locations.get(2).invariant() instanceof Expression.Quantified);
        assertEquals(1, n.startErrors().size(), () -> n.startErrors().toString());
        assertTrue(n.startErrors().get(0).message().startsWith("'forall' over clock constraints cannot be run"));
        ModelException e = assertThrows(ModelException.class, () -> load("""
                clock x;
                process P() { state A; init A; trans A -> A { guard x' == 0; }; }
                system P;
                """));
        assertEquals("a clock rate (x' == e) can only stand in an invariant", e.errors().get(0).message());
    }

    @Test
    void channelPriorityBetweenNamedChannels() throws ModelException {
        Network n = load("""
                chan a, b, c[2];
                chan priority a < b, c[1];
                process P() { state A; init A; trans A -> A { sync a!; }, A -> A { sync b?; }; }
                system P;
                """);
        assertEquals(List.of(0, 1, 0, 1), n.channelPriority());
        ModelException e = assertThrows(ModelException.class, () -> load("""
                chan a; int i;
                chan priority a < i;
                process P() { state A; init A; }
                system P;
                """));
        assertTrue(e.errors().get(0).message().contains("a channel priority lists channels"), e::getMessage);
    }

    @Test
    void aChannelOfAnotherKindForAReferenceParameter() throws ModelException {
        Network n = load("""
                broadcast chan alarm;
                chan plain[2];
                process P(urgent chan &c, broadcast chan &cs[2]) { state A; init A; trans A -> A { sync c!; }; }
                P1 = P(alarm, plain);
                system P1;
                """);
        Edge.Sync sync = n.processes().get(0).edges().get(0).sync();
        assertTrue(((Type.Channel) sync.channel().type()).broadcast(), "the process uses the channel it was given");
        ModelException e = assertThrows(ModelException.class, () -> load("""
                broadcast chan alarm;
                process P(urgent chan c) { state A; init A; }
                P1 = P(alarm);
                system P1;
                """));
        assertTrue(e.errors().get(0).message().contains("must be a urgent chan, but 'alarm' is a broadcast chan"),
                e::getMessage);
    }

    // ================================================================ statistical model checking

    @Test
    void aStatisticalModelLoadsAndSaysWhyItCannotRun() throws ModelException {
        Network n = resource("smc.xml");
        assertEquals(List.of("Pump"), n.processes().stream().map(Process::name).toList());
        assertTrue(n.processes().get(0).locations().stream().anyMatch(l -> l.kind() == Location.Kind.BRANCHPOINT));
        Map<String, Integer> features = Map.of("real numbers (double)", 6, "a hybrid clock", 11,
                "the built-in function 'random'", 35, "a branchpoint", 37, "dynamic templates", 47,
                "the external function 'log_event' of \"libsensor.so\"", 47, "a clock rate given by a clock or a real"
                + " number", 22);
        for (Map.Entry<String, Integer> f : features.entrySet()) {
            Diagnostic d = n.startErrors().stream().filter(s -> s.message().startsWith(f.getKey())).findFirst()
                    .orElseThrow(() -> new AssertionError(f.getKey() + " in " + n.startErrors()));
            assertEquals(f.getValue(), d.line(), d::format);
            assertTrue(d.message().contains(" cannot be run by DTRON's engine: "), d::format);
            assertTrue(n.warnings().stream().anyMatch(w -> w.pos() == d.pos()
                    && w.message().endsWith("'dtron run' refuses it")), () -> "check warns of " + d.format());
        }
        assertEquals(7, n.startErrors().size(), "one per kind of feature: " + n.startErrors());
        assertEquals(Query.Kind.PROBABILITY, n.queries().get(0).kind());
    }

    @Test
    void aTemplateThatNoProcessInstantiatesDoesNotStopARun() throws ModelException {
        Network n = load("""
                int i;
                process Unused() { state A; init A; trans A -> A { assign i = fint(random(2)); }; }
                process P() { state A; init A; }
                system P;
                """);
        assertTrue(n.startErrors().isEmpty(), () -> n.startErrors().toString());
        ModelException e = assertThrows(ModelException.class, () -> load("""
                int i;
                process Unused() { state A; init A; trans A -> A { assign i = random(2); }; }
                process P() { state A; init A; }
                system P;
                """));
        assertEquals("cannot assign a double to 'i' of type int", e.errors().get(0).message(),
                "it is still type-checked");
    }

    @Test
    void aProbabilityWeightIsANumberOnAnEdgeThatLeavesABranchpoint() throws ModelException {
        String model = """
                <nta><declaration>int n; clock x;</declaration>
                <template><name>P</name><location id="a"><name>A</name></location><branchpoint id="b"/><init ref="a"/>
                <transition><source ref="a"/><target ref="b"/><label kind="probability">2</label></transition>
                <transition><source ref="b"/><target ref="a"/><label kind="probability">WEIGHT</label></transition>
                </template>
                <system>system P;</system></nta>
                """;
        Network n = ModelLoader.load(XML, model.replace("WEIGHT", "n + 1"));
        assertEquals(1, n.warnings().stream().filter(w -> w.message().equals("a probability weight is ignored on an"
                + " edge that does not leave a branchpoint")).count(), () -> n.warnings().toString());
        ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load(XML,
                model.replace("WEIGHT", "n = 1")));
        assertEquals("a probability weight must not have side effects", e.errors().get(0).message());
        e = assertThrows(ModelException.class, () -> ModelLoader.load(XML, model.replace("WEIGHT", "x")));
        assertEquals("a probability weight is a number, not a clock", e.errors().get(0).message());
    }

    @Test
    void statisticalConstructsAreTypeChecked() {
        ModelException e = assertThrows(ModelException.class, () -> load("""
                double d = 1.5;
                int i;
                dynamic W(int id);
                process W(int id) { state A; init A; }
                process P() {
                state A;
                init A;
                trans A -> A { assign i = random(2.0); },
                      A -> A { assign i = fint(d, 2); },
                      A -> A { assign spawn P(); },
                      A -> A { assign spawn W(); },
                      A -> A { assign i = numOf(P); };
                }
                system P;
                """));
        List<String> messages = e.errors().stream().map(d -> d.line() + ": " + d.message()).toList();
        assertEquals(List.of("8: cannot assign a double to 'i' of type int",
                "9: 'fint' takes 1 argument, not 2",
                "10: 'P' is not a dynamic template (declare it: dynamic P(...);)",
                "11: 'W' takes 1 argument, not 0",
                "12: 'P' is not a dynamic template (declare it: dynamic P(...);)"), messages);
    }

    // ================================================================ how errors are reported

    @Test
    void oneUndeclaredNameGivesOneError() {
        ModelException e = assertThrows(ModelException.class, () -> load("""
                int a;
                process P() {
                state A { missing >= 0 };
                init A;
                trans A -> A { guard missing > 1; assign a = missing, missing = 2; },
                      A -> A { guard missing < 5; };
                }
                system P;
                """));
        assertEquals(1, e.errors().size(), e::getMessage);
        Diagnostic d = e.errors().get(0);
        assertEquals("unknown name 'missing'", d.message());
        assertEquals(3, d.line());
        assertEquals(11, d.column());
    }

    @Test
    void errorsComeSortedByPosition() throws ModelException {
        // the system line compiles Q before P, so Q's error is found first
        ModelException e = assertThrows(ModelException.class, () -> load("""
                process P() { state A; init A; trans A -> A { assign p_unknown = 1; }; }
                process Q() { state A; init A; trans A -> A { assign q_unknown = 1; }; }
                system Q, P;
                """));
        assertEquals(List.of("unknown name 'p_unknown'", "unknown name 'q_unknown'"),
                e.errors().stream().map(Diagnostic::message).toList());
        assertEquals(e.diagnostics().stream().map(Diagnostic::format).collect(Collectors.joining("\n")),
                e.getMessage());
        Network n = load("""
                int a[2];
                process P() { state A; init A; trans A -> A { assign a[2] = 1; }; }
                process Q() { state A; init A; trans A -> A { assign a[3] = 1; }; }
                system Q, P;
                """);
        assertEquals(List.of(2, 3), n.warnings().stream().map(Diagnostic::line).toList(), "warnings too");
    }

    @Test
    void anEntityOfTheDoctypeIsNotReportedAsUndeclared() {
        ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load(XML, """
                <?xml version="1.0"?>
                <!DOCTYPE nta [
                <!ENTITY LIMIT "5">
                ]>
                <nta><declaration>const int N = &LIMIT;;</declaration></nta>
                """));
        Diagnostic d = e.errors().get(0);
        assertEquals("the entity '&LIMIT;' is declared in the DOCTYPE, but DTRON reads no DTD, by design (nothing is"
                + " fetched and no entity of a DOCTYPE is expanded): write its text in place of &LIMIT;", d.message());
        assertEquals(5, d.line());
        ModelException undeclared = assertThrows(ModelException.class, () -> ModelLoader.load(XML,
                "<nta><declaration>const int N = &LIMIT;;</declaration></nta>"));
        assertTrue(undeclared.errors().get(0).message().startsWith("malformed XML: the entity '&LIMIT;' is not"
                + " declared"), undeclared::getMessage);
    }
}
