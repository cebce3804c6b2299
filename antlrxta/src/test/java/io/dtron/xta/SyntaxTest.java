package io.dtron.xta;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.xta.ast.Coord;
import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Edge;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.InterfaceSpec;
import io.dtron.xta.ast.Location;
import io.dtron.xta.ast.Nta;
import io.dtron.xta.ast.Query;
import java.util.List;
import org.junit.jupiter.api.Test;

/** The syntax stage on its own: precedence, queries, interface files, XML positions and layout. */
class SyntaxTest {

    @Test
    void operatorPrecedenceFollowsUppaal() {
        Expr e = ModelSyntax.parseExpression("e", "a || b && c == d + e * f").value();
        Expr.Binary or = assertInstanceOf(Expr.Binary.class, e);
        assertEquals(Expr.BinaryOp.OR, or.op());
        Expr.Binary and = assertInstanceOf(Expr.Binary.class, or.right());
        assertEquals(Expr.BinaryOp.AND, and.op());
        Expr.Binary eq = assertInstanceOf(Expr.Binary.class, and.right());
        Expr.Binary plus = assertInstanceOf(Expr.Binary.class, eq.right());
        assertEquals(Expr.BinaryOp.MUL, ((Expr.Binary) plus.right()).op());
        // keyword operators bind looser than assignment and ?:
        Expr.Binary imply = assertInstanceOf(Expr.Binary.class,
                ModelSyntax.parseExpression("e", "x = 1 imply y ? 1 : 2").value());
        assertEquals(Expr.BinaryOp.IMPLY, imply.op());
        assertInstanceOf(Expr.Assign.class, imply.left());
        assertInstanceOf(Expr.Conditional.class, imply.right());
        Expr.Quantifier q = assertInstanceOf(Expr.Quantifier.class,
                ModelSyntax.parseExpression("e", "forall (i : id_t) a[i] imply b").value());
        assertInstanceOf(Expr.Binary.class, q.body(), "the quantifier takes everything after it");
    }

    @Test
    void queriesOfAQFile() {
        Parsed<List<Query>> parsed = ModelSyntax.parseQueries("m.q", """
                // a comment
                E<> Train(0).Cross and Train(1).Stop
                A[] not deadlock
                A<> P.done
                E[ ] x < 3
                p.a --> q.b
                """);
        assertFalse(parsed.hasErrors(), parsed.diagnostics().toString());
        assertEquals(List.of(Query.Kind.EXISTS_EVENTUALLY, Query.Kind.ALWAYS_GLOBALLY, Query.Kind.ALWAYS_EVENTUALLY,
                Query.Kind.EXISTS_GLOBALLY, Query.Kind.LEADS_TO), parsed.value().stream().map(Query::kind).toList());
        assertEquals(3, parsed.value().get(1).pos().line());
        Parsed<List<Query>> bad = ModelSyntax.parseQueries("m.q", "E<> \nA[] x <");
        assertTrue(bad.hasErrors());
        assertEquals(2, bad.diagnostics().get(0).line());
    }

    @Test
    void statisticalAndStrategyQueriesOfAQFile() {
        Parsed<List<Query>> parsed = ModelSyntax.parseQueries("m.q", """
                simulate 10 [<=100] {x, y}
                Pr[<=10](<> P.done) >= 0.5
                E[#<=3](min: n)
                strategy S = control: A[] safe
                E<> P.done under S
                loadStrategy {n} -> {x} ("s.json")
                inf{P.idle}: x
                """);
        assertFalse(parsed.hasErrors(), parsed.diagnostics().toString());
        assertEquals(List.of(Query.Kind.SIMULATE, Query.Kind.PROBABILITY, Query.Kind.EXPECTATION,
                Query.Kind.STRATEGY, Query.Kind.EXISTS_EVENTUALLY, Query.Kind.STRATEGY_FILE, Query.Kind.VALUE_BOUNDS),
                parsed.value().stream().map(Query::kind).toList());
        Query under = parsed.value().get(4);
        assertEquals("S", under.strategy());
        assertEquals("E<> P.done under S", under.text());
        assertInstanceOf(Expr.Field.class, under.formula());
    }

    @Test
    void powerBindsTighterThanProductAndToTheRight() {
        Expr.Binary times = assertInstanceOf(Expr.Binary.class, ModelSyntax.parseExpression("e", "a * b ** c ** d").value());
        assertEquals(Expr.BinaryOp.MUL, times.op());
        Expr.Binary pow = assertInstanceOf(Expr.Binary.class, times.right());
        assertEquals(Expr.BinaryOp.POW, pow.op());
        assertEquals(Expr.BinaryOp.POW, assertInstanceOf(Expr.Binary.class, pow.right()).op());
    }

    @Test
    void declarationsOfStatisticalModels() {
        Parsed<Nta> parsed = ModelSyntax.parseXta("m.xta", """
                import "lib.so" { int f(int, int &b); double g(double x) = c_g; };
                dynamic W(int id);
                chan a, b;
                chan priority a < b;
                process W(int id) { state A; init A; trans A -> A { assign spawn W(id + 1); }; }
                system W;
                """);
        assertFalse(parsed.hasErrors(), parsed.diagnostics().toString());
        List<Decl> decls = parsed.value().declarations();
        Decl.External f = assertInstanceOf(Decl.External.class, decls.get(0));
        assertEquals("lib.so", f.library());
        assertEquals(List.of("", "b"), f.params().stream().map(io.dtron.xta.ast.Param::name).toList());
        assertTrue(f.params().get(1).reference());
        assertEquals("g", assertInstanceOf(Decl.External.class, decls.get(1)).name());
        assertEquals("W", assertInstanceOf(Decl.Dynamic.class, decls.get(2)).name());
        Decl.ChanPriority priority = assertInstanceOf(Decl.ChanPriority.class, decls.get(5));
        assertEquals(2, priority.levels().size(), "'<' separates two levels");
        Decl.Template w = assertInstanceOf(Decl.Template.class, decls.get(6));
        Expr.Spawn spawn = assertInstanceOf(Expr.Spawn.class, w.edges().get(0).updates().get(0));
        assertEquals("W", spawn.template());
        assertEquals(1, spawn.args().size());
    }

    @Test
    void tronInterfaceFile() {
        Parsed<InterfaceSpec> parsed = ModelSyntax.parseInterface("l.trn", """
                input grasp(), release();
                output level(adapLevel, other);
                precision 1000;
                timeout 500;
                """);
        assertFalse(parsed.hasErrors());
        InterfaceSpec spec = parsed.value();
        assertEquals(List.of("grasp", "release"), spec.inputs().stream().map(InterfaceSpec.Channel::name).toList());
        assertEquals(List.of("adapLevel", "other"),
                spec.outputs().get(0).variables().stream().map(InterfaceSpec.Variable::name).toList());
        assertEquals(1000L, spec.precision());
        assertEquals(500L, spec.timeout());
        Parsed<InterfaceSpec> bad = ModelSyntax.parseInterface("l.trn", "input a()\noutput b();");
        assertEquals("l.trn:2:1: error: syntax error: unexpected 'output', expected ',' or ';'",
                bad.diagnostics().get(0).format());
    }

    @Test
    void xmlLabelPositionsPointIntoTheFileThroughEntities() {
        String xml = """
                <nta><declaration>clock x;</declaration>
                <template><name x="5" y="6">T</name>
                <location id="a" x="10" y="20"><name x="11" y="21">A</name><label kind="invariant" x="12" y="22">x &lt;= 3</label></location>
                <init ref="a"/>
                <transition><source ref="a"/><target ref="a"/><label kind="guard" x="1" y="2">x &gt;= 1 &amp;&amp; $</label><nail x="7" y="8"/></transition>
                </template><system>system T;</system></nta>
                """;
        Parsed<Nta> parsed = ModelSyntax.parseXml("t.xml", xml);
        assertEquals(1, parsed.diagnostics().size());
        Diagnostic d = parsed.diagnostics().get(0);
        // the label text starts at file column 79; in "x &gt;= 1 &amp;&amp; $" the '$' is at column 100 of the
        // file and, decoded ("x >= 1 && $"), the 11th character of the label
        assertEquals(5, d.line());
        assertEquals(100, d.column());
        assertEquals("T", d.template());
        assertEquals("guard", d.labelKind());
        assertEquals(11, d.pos().columnInFragment());
        assertEquals("t.xml:5:100: error: syntax error: unexpected character '$' (template T, guard label, column 11)",
                d.format());
    }

    @Test
    void anXtaErrorNamesItsTemplateAndLabelAndOneBadLabelIsOneError() {
        String xta = """
                // a comment with process X() { trans A -> B { guard x; }; }
                chan c;
                int g;
                process Server() {
                    clock x;
                    int[0,9] n = g +;
                    state Idle, Busy { x <= 3 + };
                    init Idle;
                    trans Idle -> Busy { sync c?; assign x = 0; },
                          Busy -> Idle { guard x >= ; sync c!; assign n = (n + 1) % 10; };
                }
                process Client() { state A; init A; trans A -> A { select v : int[0,9]; sync c!; assign g = v +; }; }
                system Server, Client;
                """;
        List<String> errors = ModelSyntax.parseXta("s.xta", xta).diagnostics().stream().map(Diagnostic::format)
                .toList();
        assertEquals(List.of(
                "s.xta:6:21: error: syntax error: an operand is missing after '+' (template Server, declaration)",
                "s.xta:7:33: error: syntax error: an operand is missing after '+' (template Server, invariant label)",
                "s.xta:10:37: error: syntax error: an operand is missing after '>=' (template Server, guard label)",
                "s.xta:12:96: error: syntax error: an operand is missing after '+' (template Client, assignment"
                        + " label)"), errors);
        Parsed<Nta> unknown = ModelSyntax.parseXta("u.xta", "chan c;\nprocess P() { state A; init A; trans A -> A"
                + " { guard y > 1; sync c!; }; }\nsystem P;\n");
        assertTrue(unknown.diagnostics().isEmpty(), "names are resolved later: " + unknown.diagnostics());
        assertEquals("P", Fragment.ofXtaFile("u.xta", "process P() { state A { x <= 1 }; }").templateAt(25));
        assertEquals("invariant", Fragment.ofXtaFile("u.xta", "process P() { state A { x <= 1 }; }").kindAt(25));
    }

    @Test
    void xmlLayoutIsKept() {
        String xml = """
                <nta><template><name x="5" y="6">T</name>
                <location id="a" x="10" y="20"><name x="11" y="21">A</name><label kind="invariant" x="12" y="22">true</label><committed/></location>
                <init ref="a"/>
                <transition><source ref="a"/><target ref="a"/><label kind="synchronisation" x="1" y="2">c!</label><nail x="7" y="8"/></transition>
                </template><system>system T;</system></nta>
                """;
        Decl.Template t = ModelSyntax.parseXml("t.xml", xml).value().templates().get(0);
        assertEquals(new Coord(5, 6), t.coord());
        Location a = t.locations().get(0);
        assertEquals(new Coord(10, 20), a.coord());
        assertEquals(Location.Kind.COMMITTED, a.kind());
        assertEquals(List.of(new Coord(11, 21), new Coord(12, 22)), a.labels().stream().map(l -> l.coord()).toList());
        Edge e = t.edges().get(0);
        assertEquals(List.of(new Coord(7, 8)), e.nails());
        assertEquals(new Coord(1, 2), e.labels().get(0).coord());
        assertEquals(Edge.Direction.SEND, e.sync().direction());
    }
}
