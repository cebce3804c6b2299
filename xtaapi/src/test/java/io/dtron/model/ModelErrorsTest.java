package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertDoesNotThrow;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.xta.Diagnostic;
import java.util.List;
import java.util.stream.Collectors;
import org.junit.jupiter.api.Test;

/**
 * Malformed and ill-typed models: each must be rejected with a {@link ModelException} whose diagnostics name
 * the problem and its exact place (file, line, column; for XML labels also the template, the label kind and
 * the column inside the label). A few near-identical correct models are loaded as controls, so that the
 * rejections are not the work of a broken skeleton.
 *
 * <p>All expected positions were counted by hand from the model texts below. Text blocks are written with
 * the closing delimiter at the same indentation as their content, so every line of a model starts at
 * column 1 unless it is indented on purpose.
 */
class ModelErrorsTest {

    private static final String XTA = "m.xta";
    private static final String XML = "m.xml";
    private static final String TRN = "m.trn";

    // =============================================================================================== controls

    /** The XTA skeleton most XTA tests below are variations of. */
    private static final String GOOD_XTA = """
            clock x;
            chan a;
            int i;
            int f(int p, int q) { return p + q; }
            void inc(int &r) { r++; }
            process P() {
            state A, B;
            init A;
            trans A -> B { guard x > 1 && i != 5; sync a!; assign i = f(1, 2), inc(i); };
            }
            system P;
            """;

    @Test
    void controlTheXtaSkeletonLoads() throws ModelException {
        Network n = ModelLoader.load(XTA, GOOD_XTA);
        assertEquals(1, n.processes().size());
        assertEquals(1, n.clockCount());
        assertEquals(1, n.channelCount());
    }

    @Test
    void controlTheXmlSkeletonLoadsWithEntitiesInEveryLabel() throws ModelException {
        Network n = ModelLoader.load(XML, xml()
                .global("clock x; chan a; int i; const int N = 3; urgent chan u;")
                .parameters("const int[0,2] id")
                .local("int[0,3] r = 3;")
                .invariant("x &lt;= 5 &amp;&amp; i &lt; N")
                .select("k : int[0,2]")
                .guard("x &lt; 3 &amp;&amp; i &lt; 2 &amp;&amp; k &gt;= 0")
                .sync("a!")
                .assign("i = k, x = 0, r = id")
                .text());
        assertEquals(List.of("P(0)", "P(1)", "P(2)"), n.processes().stream().map(Process::name).toList());
    }

    @Test
    void controlCorrectedVersionsOfRejectedModelsLoad() throws ModelException {
        // the same texts as below with the one mistake removed: each loads, with what it declares
        Network declarations = ModelLoader.load(XTA, """
                int i = 0;
                clock x;
                int[0,3] v = 3;
                int a[3] = {1, 2, 3};
                const int n = 3;
                int b[n];
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertArrayEquals(new int[] {0}, declarations.variable("i").orElseThrow().initial());
        assertArrayEquals(new int[] {3}, declarations.variable("v").orElseThrow().initial());
        assertArrayEquals(new int[] {1, 2, 3}, declarations.variable("a").orElseThrow().initial());
        assertArrayEquals(new int[] {0, 0, 0}, declarations.variable("b").orElseThrow().initial(), "b[n], n = 3");
        assertTrue(declarations.clock("x").isPresent());
        assertEquals(List.of("P"), declarations.processes().stream().map(Process::name).toList());

        Network labels = ModelLoader.load(XML, xml().global("clock x; chan a; int i; const int N = 3;")
                .guard("x &lt; 1 &amp;&amp; i &lt;= 2").assign("i = 1, i := 4").text());
        Edge edge = labels.process("P").orElseThrow().edges().get(0);
        assertNotNull(edge.guard(), "the guard");
        assertEquals(2, edge.updates().size(), "both assignments: " + edge.updates());
        assertTrue(labels.channel("a").isPresent());

        Network expanded = ModelLoader.load(XML, xml().parameters("const int[0,1] id").system("system P;").text());
        assertEquals(2, expanded.processes().size(), "P(0) and P(1): " + expanded.processes());

        Network instantiated = ModelLoader.load(XTA, """
                chan c;
                clock x;
                int[0,3] v;
                process P(chan &b, clock &y, int[0,3] &r, int k) {
                state A;
                init A;
                trans A -> A { sync b!; };
                }
                Q = P(c, x, v, 1);
                system Q;
                """);
        Edge sync = instantiated.process("Q").orElseThrow().edges().get(0);
        assertNotNull(sync.sync(), "Q's edge sends on the channel passed by reference");
    }

    @Test
    void controlTheInterfaceOfANetworkResolves() throws ModelException {
        Network n = ModelLoader.load(XTA, INTERFACE_MODEL);
        TestInterface byFile = TestInterface.fromText(n, TRN, """
                input i_go(i_go_speed);
                output o_done;
                precision 1000;
                timeout 100;
                """);
        assertEquals("i_go_speed", byFile.input("i_go").orElseThrow().variables().get(0).name());
        TestInterface byName = TestInterface.fromNames(n);
        assertEquals("speed", byName.input("go").orElseThrow().variables().get(0).name());
    }

    // =============================================================================================== syntax, XTA

    @Test
    void missingSemicolon() {
        ModelException e = rejected(XTA, """
                int i = 0
                clock x;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        // reported at the token where ';' was expected
        assertError(onlyError(e), "syntax error: unexpected 'clock', expected ',' or ';'", 2, 1);
    }

    @Test
    void unexpectedToken() {
        ModelException e = rejected(XTA, """
                clock x;
                int k = 3 * / 2;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "syntax error: unexpected '/'", 2, 13);
    }

    @Test
    void unexpectedCharacterDollar() {
        ModelException e = rejected(XTA, """
                clock x;
                int $a;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "syntax error: unexpected character '$'", 2, 5);
    }

    @Test
    void unterminatedBlockComment() {
        ModelException e = rejected(XTA, """
                clock x;
                process P() {
                state A;
                init A;
                }
                system P;
                /* this comment is never closed
                """);
        assertError(onlyError(e), "a comment starts here with '/*' but never ends with '*/'", 7, 1);
    }

    @Test
    void severalSyntaxErrorsInOneFileAreAllReported() {
        ModelException e = rejected(XTA, """
                int a = ;
                clock x;
                clock y z;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertEquals(2, e.errors().size(), e.getMessage());
        assertError(e.errors().get(0), "syntax error: an operand is missing after '='", 1, 9);
        assertError(e.errors().get(1), "syntax error: unexpected 'z'", 3, 9);
    }

    @Test
    void danglingOperatorIsReportedWhereTheOperandIsMissing() {
        // an operand missing after '*' (or '/', '<=', '==', '&&'...) is reported at the ';' that stands where it
        // should be...
        ModelException times = rejected(XTA, """
                int b = 3 + 4 * ;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(times), "syntax error: an operand is missing after '*'", 1, 17);
        // ...and so is one missing after '+' (and '-', '<', '?'), though these can also end an expression elsewhere
        ModelException plus = rejected(XTA, """
                int b = 3 +;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(plus), "syntax error: an operand is missing after '+'", 1, 12);
    }

    // =============================================================================================== syntax, XML

    @Test
    void unexpectedCharacterInAnXmlGuardAfterEntities() {
        // raw label:     x &lt; 1 &amp;&amp; @   -> '@' is the 21st character of the raw text
        // decoded label: x < 1 && @              -> '@' is the 10th character of the label
        ModelException e = rejected(XML, xml().guard("x &lt; 1 &amp;&amp; @").text());
        Diagnostic d = onlyError(e);
        assertError(d, "syntax error: unexpected character '@'", 15, 21 + 20);
        assertInLabel(d, "P", "guard", 10);
        assertTrue(d.format().endsWith(" (template P, guard label, column 10)"), d.format());
    }

    @Test
    void syntaxErrorInAnXmlAssignmentLabel() {
        ModelException e = rejected(XML, xml().assign("i = 1 j = 2").text());
        Diagnostic d = onlyError(e);
        assertError(d, "syntax error: unexpected 'j'", 17, 26 + 6);
        assertInLabel(d, "P", "assignment", 7);
    }

    @Test
    void syntaxErrorInAMultiLineGlobalDeclaration() {
        ModelException e = rejected(XML, """
                <?xml version="1.0" encoding="utf-8"?>
                <nta>
                <declaration>// globals
                clock x;
                int i = 2 *;
                </declaration>
                <template>
                <name>P</name>
                <location id="id0"><name>A</name></location>
                <init ref="id0"/>
                </template>
                <system>system P;</system>
                </nta>
                """);
        Diagnostic d = onlyError(e);
        assertError(d, "syntax error: an operand is missing after '*'", 5, 12);
        assertInLabel(d, null, "declaration", 12);
        assertTrue(d.format().endsWith(" (declaration, column 12)"), d.format());
    }

    @Test
    void syntaxErrorInTheXmlSystemSection() {
        ModelException e = rejected(XML, xml().system("system P Q;").text());
        Diagnostic d = onlyError(e);
        assertError(d, "syntax error: unexpected 'Q'", 20, 9 + 9);
        assertInLabel(d, null, "system", 10);
    }

    @Test
    void syntaxErrorsInTwoXmlLabelsAreBothReported() {
        ModelException e = rejected(XML, xml().local("int j = ;").guard("i &lt; 1 2").text());
        assertEquals(2, e.errors().size(), e.getMessage());
        Diagnostic declaration = e.errors().get(0);
        assertError(declaration, "syntax error: an operand is missing after '='", 7, 14 + 8);
        assertInLabel(declaration, "P", "declaration", 9);
        // raw "i &lt; 1 2": the '2' is at raw offset 9; decoded "i < 1 2": the 7th character
        Diagnostic guard = e.errors().get(1);
        assertError(guard, "syntax error: unexpected '2'", 15, 21 + 9);
        assertInLabel(guard, "P", "guard", 7);
    }

    @Test
    void danglingOperatorAtTheEndOfAnXmlGuard() {
        // decoded "i <" ends at raw offset 6 (after "&lt;"): the missing operand is reported there
        ModelException e = rejected(XML, xml().guard("i &lt;").text());
        Diagnostic d = onlyError(e);
        assertError(d, "syntax error: an operand is missing after '<'", 15, 21 + 6);
        assertInLabel(d, "P", "guard", 4);
    }

    @Test
    void positionsInAFileWithCrLfLineEnds() {
        ModelException e = rejected(XML, xml().guard("i == 0 &amp;&amp; x").text().replace("\n", "\r\n"));
        Diagnostic d = onlyError(e);
        assertError(d, "'&&' needs booleans or clock constraints, not a clock", 15, 21 + 18);
        assertInLabel(d, "P", "guard", 11);
    }

    @Test
    void malformedXmlWithAnUnclosedTag() {
        ModelException e = rejected(XML, """
                <?xml version="1.0" encoding="utf-8"?>
                <nta>
                <declaration>int i;</declaration>
                <template>
                <name>P</name>
                <location id="id0"><name>A</name>
                <init ref="id0"/>
                </template>
                <system>system P;</system>
                </nta>
                """);
        Diagnostic d = onlyError(e);
        assertTrue(d.message().startsWith("malformed XML: "), d.format());
        // where the XML parser notices the problem: inside the </template> tag that does not match
        assertError(d, "The element type \"location\" must be terminated by the matching end-tag", 8, 3);
    }

    @Test
    void xmlWhoseRootIsNotNta() {
        ModelException e = rejected(XML, """
                <?xml version="1.0" encoding="utf-8"?>
                <model>
                <declaration>int i;</declaration>
                </model>
                """);
        Diagnostic d = onlyError(e);
        assertEquals("not an Uppaal model: the root element is <model>, expected <nta>", d.message());
        assertError(d, "expected <nta>", 2, 1);
    }

    // =============================================================================================== names and types

    @Test
    void unknownName() {
        // decoded guard: "i <= 2 && k == 1"
        ModelException e = rejected(XML, xml().guard("i &lt;= 2 &amp;&amp; k == 1").text());
        Diagnostic d = onlyError(e);
        assertEquals("unknown name 'k'", d.message());
        assertError(d, "unknown name 'k'", 15, 21 + 21);
        assertInLabel(d, "P", "guard", 11);
    }

    @Test
    void unknownType() {
        ModelException e = rejected(XTA, """
                clock x;
                process P() {
                  foo n;
                  state A;
                  init A;
                }
                system P;
                """);
        assertError(onlyError(e), "unknown type 'foo'", 3, 3);
    }

    @Test
    void typeUsedAsAValue() {
        ModelException e = rejected(XTA, """
                typedef int[0,3] T;
                int i = T;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "'T' is a type, not a value", 2, 9);
    }

    @Test
    void duplicateDeclarationInOneScope() {
        ModelException e = rejected(XTA, """
                int i;
                clock c;
                bool i;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "'i' is already declared at line 1", 3, 6);
    }

    // =============================================================================================== assignments

    @Test
    void assigningToAConstant() {
        ModelException e = rejected(XML, xml().global("clock x; chan a; int i; const int N = 3;")
                .assign("i = 1, N := 4").text());
        Diagnostic d = onlyError(e);
        assertError(d, "cannot assign to 'N': 'N' is a constant", 17, 26 + 7);
        assertInLabel(d, "P", "assignment", 8);
    }

    @Test
    void assigningToAFreeParameter() {
        // the situation of decl-04.xta: a free parameter used as a local variable
        ModelException e = rejected(XTA, """
                const int N = 5;

                process Proc(int[1,N] pid) {
                state A, B;
                init A;
                trans
                  A -> B { guard pid < N; assign pid++; };
                }

                system Proc;
                """);
        // one message, although the template is compiled for each of the 5 processes
        assertError(onlyError(e), "cannot assign to 'pid': 'pid' is a free parameter of Proc", 7, 34);
    }

    @Test
    void indexingANonArray() {
        ModelException e = rejected(XML, xml().assign("i = 2, i[0] = 1").text());
        Diagnostic d = onlyError(e);
        assertError(d, "'i' is not an array (it is an integer)", 17, 26 + 7);
        assertInLabel(d, "P", "assignment", 8);
    }

    // =============================================================================================== clocks

    @Test
    void clockComparedWithABoolean() {
        // Uppaal (utap) compares clocks with integers only; bool is not an integer there
        // decoded guard: "x <= b"
        ModelException e = rejected(XML, xml().global("clock x; chan a; int i; bool b;").guard("x &lt;= b").text());
        Diagnostic d = onlyError(e);
        assertError(d, "cannot compare a clock with a boolean", 15, 21 + 8);
        assertInLabel(d, "P", "guard", 6);
    }

    @Test
    void clockUsedAsABoolean() {
        ModelException e = rejected(XML, xml().guard("i == 0 &amp;&amp; x").text());
        Diagnostic d = onlyError(e);
        assertError(d, "'&&' needs booleans or clock constraints, not a clock", 15, 21 + 18);
        assertInLabel(d, "P", "guard", 11);
    }

    @Test
    void clockInIntegerArithmetic() throws ModelException {
        // decoded guard: "i == 0 && x % 2 < 3"; x * 2 is a double in Uppaal 5 (statistical model checking), x % 2 is
        // nothing
        ModelException e = rejected(XML, xml().guard("i == 0 &amp;&amp; x % 2 &lt; 3").text());
        Diagnostic d = onlyError(e);
        assertError(d, "'%' needs integers, not a clock", 15, 21 + 18);
        assertInLabel(d, "P", "guard", 11);
        Network n = ModelLoader.load(XML, xml().guard("i == 0 &amp;&amp; x * 2 &lt; 3").text());
        assertTrue(n.startErrors().get(0).message().startsWith("a clock used as a real number"), n::toString);
    }

    @Test
    void clockNotEqualInAGuard() {
        ModelException e = rejected(XTA, """
                clock x;
                process P() {
                state A, B;
                init A;
                trans A -> B { guard x != 5; };
                }
                system P;
                """);
        assertError(onlyError(e), "'!=' on clocks, negations of clock constraints and disjunctions of two clock constraints are not allowed",
                5, 22);
    }

    @Test
    void disjunctionOfClockConstraintsInAGuard() {
        ModelException e = rejected(XML, xml().global("clock x, y; chan a; int i;").guard("x &lt; 1 || y > 2").text());
        Diagnostic d = onlyError(e);
        assertError(d, "negations of clock constraints and disjunctions of two clock constraints are not allowed", 15, 21);
        assertInLabel(d, "P", "guard", 1);
    }

    @Test
    void equalityUsedAsAnInvariant() {
        // decoded invariant: "x <= 5 && x == 3"; as in Uppaal, bounds (also lower ones) may stand in invariants,
        // '==' may not
        ModelException e = rejected(XML, xml().invariant("x &lt;= 5 &amp;&amp; x == 3").text());
        Diagnostic d = onlyError(e);
        assertError(d, "an invariant is a conjunction of bounds on clocks", 8, 58 + 21);
        assertTrue(d.message().endsWith("'x == 3' is not"), d.format());
        assertInLabel(d, "P", "invariant", 11);
        assertDoesNotThrow(() -> ModelLoader.load(XML, xml().invariant("x &lt;= 5 &amp;&amp; x > 3").text()));
    }

    @Test
    void urgentChannelEdgeWithAClockGuardIsAWarningAsInUppaal() throws ModelException {
        // Uppaal warns "Clock guards are not allowed on urgent edges" and runs the model in statistical model
        // checking only; DTRON loads it and refuses to run it
        Network n = ModelLoader.load(XML, xml().global("clock x; urgent chan u; int i;").guard("x > 1").sync("u!")
                .text());
        Diagnostic d = n.warnings().stream().filter(w -> w.message().startsWith("a clock guard on an edge that"
                + " synchronises on an urgent channel")).findFirst().orElseThrow(() -> new AssertionError(n.warnings()));
        assertEquals(15, d.line(), d::format);
        assertEquals(21, d.column(), d::format);
        assertInLabel(d, "P", "guard", 1);
        assertEquals(d.pos(), n.startErrors().get(0).pos());
    }

    // =============================================================================================== edges

    @Test
    void sideEffectInAGuard() {
        ModelException e = rejected(XTA, """
                int i;
                process P() {
                state A, B;
                init A;
                trans A -> B { guard i++ > 0; };
                }
                system P;
                """);
        assertError(onlyError(e), "a guard must not have side effects", 5, 22);
    }

    @Test
    void synchronisationOnAClock() {
        ModelException e = rejected(XML, xml().sync("x!").text());
        Diagnostic d = onlyError(e);
        assertError(d, "a synchronisation needs a channel, but 'x' is a clock", 16, 31);
        assertInLabel(d, "P", "synchronisation", 1);
    }

    @Test
    void synchronisationOnAnInt() {
        ModelException e = rejected(XTA, """
                int i;
                process P() {
                state A, B;
                init A;
                trans A -> B { sync i?; };
                }
                system P;
                """);
        assertError(onlyError(e), "a synchronisation needs a channel, but 'i' is an integer", 5, 21);
    }

    @Test
    void selectOverAnUnboundedInt() {
        ModelException e = rejected(XML, xml().select("k : int").text());
        Diagnostic d = onlyError(e);
        assertError(d, "select 'k' needs a bounded integer range or a scalar set, not int", 14, 22 + 4);
        assertInLabel(d, "P", "select", 5);
    }

    @Test
    void scalarComparedWithAnInt() {
        ModelException e = rejected(XTA, """
                typedef scalar[3] S;
                S s;
                process P() {
                state A, B;
                init A;
                trans A -> B { guard s == 1; };
                }
                system P;
                """);
        assertError(onlyError(e), "a scalar value can only be compared with a value of the same scalar set", 6, 22);
    }

    @Test
    void cspAndIoSynchronisationsMixed() {
        ModelException e = rejected(XTA, """
                chan a, b;
                process P() {
                state A;
                init A;
                trans A -> A { sync a!; }, A -> A { sync b; };
                }
                system P;
                """);
        assertError(onlyError(e), "cannot be mixed in one model", 5, 42);
    }

    // =============================================================================================== functions

    @Test
    void wrongNumberOfFunctionArguments() {
        ModelException e = rejected(XTA, """
                int f(int a, int b) { return a + b; }
                int i;
                process P() {
                state A, B;
                init A;
                trans A -> B { assign i = f(1); };
                }
                system P;
                """);
        assertError(onlyError(e), "'f' takes 2 arguments, not 1", 6, 27);
    }

    @Test
    void referenceArgumentThatIsNotAVariable() {
        ModelException e = rejected(XTA, """
                void inc(int &x) { x++; }
                process P() {
                state A, B;
                init A;
                trans A -> B { assign inc(1); };
                }
                system P;
                """);
        assertError(onlyError(e), "argument 1 of 'inc' is passed by reference, so it must be a variable", 5, 27);
    }

    @Test
    void returnWithoutAValueInAnIntFunction() {
        ModelException e = rejected(XTA, """
                int f() {
                  return;
                }
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "'f' returns int: 'return' needs a value", 2, 3);
    }

    @Test
    void valueReturnedFromAVoidFunction() {
        ModelException e = rejected(XTA, """
                void g() {
                  return 1;
                }
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "'g' returns nothing (void), so 'return' takes no value", 2, 10);
    }

    @Test
    void breakOutsideALoop() {
        ModelException e = rejected(XTA, """
                int i;
                void h() {
                  while (i < 3) { i++; }
                  break;
                }
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "'break' outside a loop", 4, 3);
    }

    // =============================================================================================== declarations

    @Test
    void arraySizeNotConstant() {
        ModelException e = rejected(XTA, """
                int n = 3;
                int a[n];
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "an array size must be computable at compile time", 2, 7);
    }

    @Test
    void emptyIntegerRange() {
        ModelException e = rejected(XML, xml().local("int[5,1] r;").text());
        Diagnostic d = onlyError(e);
        assertEquals("the integer range [5,1] is empty", d.message());
        assertError(d, "is empty", 7, 14);
        assertInLabel(d, "P", "declaration", 1);
    }

    @Test
    void initialiserWithTheWrongNumberOfElements() {
        ModelException e = rejected(XTA, """
                int a[3] = {1, 2};
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        assertError(onlyError(e), "'a' has 3 elements, but the initialiser gives 2", 1, 12);
    }

    @Test
    void initialValueOutsideTheRange() {
        ModelException e = rejected(XTA, """
                int[0,3] x = 7;
                process P() {
                state A;
                init A;
                }
                system P;
                """);
        Diagnostic d = onlyError(e);
        assertEquals("the initial value 7 of 'x' is outside its range int[0,3]", d.message());
        assertError(d, "outside its range", 1, 14);
    }

    // =============================================================================================== templates

    @Test
    void duplicateLocationNames() {
        ModelException e = rejected(XML, """
                <?xml version="1.0" encoding="utf-8"?>
                <nta>
                <template>
                <name>P</name>
                <location id="id0"><name>A</name></location>
                <location id="id1"><name>A</name></location>
                <init ref="id0"/>
                </template>
                <system>system P;</system>
                </nta>
                """);
        Diagnostic d = onlyError(e);
        assertError(d, "template P has two locations called 'A'", 6, 26);
        assertEquals("P", d.template(), d.format());
    }

    @Test
    void edgeToAnUnknownLocation() {
        ModelException e = rejected(XML, xml().target("id9").text());
        Diagnostic d = onlyError(e);
        // reported at the <transition> tag
        assertError(d, "the edge's target 'id9' is not a location of template P", 11, 1);
        assertEquals("P", d.template(), "the template of " + d.format());
    }

    @Test
    void templateWithLocationsButNoInit() {
        ModelException e = rejected(XML, xml().init("<!-- no init -->").text());
        Diagnostic d = onlyError(e);
        // reported at the template's name
        assertError(d, "template P has no initial location", 5, 7);
        assertEquals("P", d.template(), "the template of " + d.format());
    }

    @Test
    void freeParameterOfUnboundedIntType() {
        ModelException e = rejected(XML, xml().parameters("int id").text());
        Diagnostic d = onlyError(e);
        assertError(d, "free parameter 'id' of P must be a bounded integer or a scalar passed by value", 6, 12 + 4);
        assertInLabel(d, "P", "parameter", 5);
    }

    // =============================================================================================== the system line

    @Test
    void systemLineNamingAnUnknownTemplate() {
        ModelException e = rejected(XML, xml().system("system P, Q;").text());
        Diagnostic d = onlyError(e);
        assertError(d, "'Q' in the system line is not declared", 20, 9 + 10);
        assertInLabel(d, null, "system", 11);
    }

    @Test
    void nameListedTwiceInTheSystemLine() {
        ModelException e = rejected(XTA, """
                process P() {
                state A;
                init A;
                }
                system P < P;
                """);
        assertError(onlyError(e), "'P' is listed twice in the system line", 5, 12);
    }

    @Test
    void modelWithoutASystemLine() {
        ModelException e = rejected(XTA, """
                clock x;
                process P() {
                state A;
                init A;
                }
                """);
        Diagnostic d = onlyError(e);
        assertNull(d.pos(), "a whole-file error has no position");
        assertEquals(0, d.line());
        assertEquals(0, d.column());
        assertEquals("m.xta: error: the model has no system line (system P, Q;)", d.format());
    }

    // =============================================================================================== parameters

    @Test
    void valueParameterGivenANonConstantArgument() {
        ModelException e = rejected(XTA, """
                int v = 1;
                process P(int k) {
                state A;
                init A;
                }
                Q = P(v);
                system Q;
                """);
        assertError(onlyError(e),
                "the argument for parameter 'k' of P is passed by value, so it must be computable at compile time",
                6, 7);
    }

    @Test
    void referenceParameterWithTheWrongType() {
        ModelException e = rejected(XTA, """
                int[0,3] v;
                process P(int &r) {
                state A;
                init A;
                }
                Q = P(v);
                system Q;
                """);
        assertError(onlyError(e),
                "the argument for parameter 'r' of P must be exactly int (it is passed by reference), not int[0,3]",
                6, 7);
    }

    @Test
    void channelPassedWhereABroadcastChannelIsRequired() {
        ModelException e = rejected(XTA, """
                chan c;
                process P(broadcast chan b) {
                state A;
                init A;
                trans A -> A { sync b!; };
                }
                Q = P(c);
                system Q;
                """);
        assertError(onlyError(e), "the argument for parameter 'b' of P must be a broadcast chan, but 'c' is a chan",
                7, 7);
    }

    @Test
    void clockParameterPassedByValue() {
        ModelException e = rejected(XTA, """
                clock x;
                process P(clock c) {
                state A;
                init A;
                }
                Q = P(x);
                system Q;
                """);
        assertError(onlyError(e), "the argument for parameter 'c' of P: a clock parameter must be a reference (clock &c)",
                6, 7);
    }

    // =============================================================================================== test interface

    private static final String INTERFACE_MODEL = """
            chan i_go, o_done;
            int i_go_speed;
            process P() {
            state A;
            init A;
            trans A -> A { sync i_go?; }, A -> A { sync o_done!; };
            }
            system P;
            """;

    @Test
    void interfaceFileNamingAnUnknownChannelAndAnUnknownVariable() throws ModelException {
        Network n = ModelLoader.load(XTA, INTERFACE_MODEL);
        ModelException e = assertThrows(ModelException.class, () -> TestInterface.fromText(n, TRN, """
                input i_go(speed), i_stop;
                output o_done;
                precision 1000;
                """));
        checkDiagnostics(TRN, e);
        assertEquals(2, e.errors().size(), e.getMessage());
        assertError(e.errors().get(0), "variable 'speed' attached to input 'i_go' is not a global variable of m.xta",
                1, 12);
        assertError(e.errors().get(1), "input 'i_stop' is not a global channel of m.xta", 1, 20);
    }

    @Test
    void attachedVariableByNameThatIsAnArray() throws ModelException {
        Network n = ModelLoader.load(XTA, """
                chan i_move;
                int i_move_steps[3];
                process P() {
                state A;
                init A;
                trans A -> A { sync i_move?; };
                }
                system P;
                """);
        ModelException e = assertThrows(ModelException.class, () -> TestInterface.fromNames(n));
        checkDiagnostics(XTA, e);
        assertError(onlyError(e), "'i_move_steps' is attached to channel 'i_move' by its name, so it must be an int"
                + " or bool, not int[3]", 2, 5);
    }

    // =============================================================================================== helpers

    /** Loads {@code text}, which must fail with a ModelException, and checks what every diagnostic must satisfy. */
    private static ModelException rejected(String name, String text) {
        ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load(name, text),
                name + " must be rejected");
        checkDiagnostics(name, e);
        return e;
    }

    /** Non-empty messages; the file name; "file:line:column: error: " for positioned errors. */
    private static void checkDiagnostics(String file, ModelException e) {
        assertFalse(e.errors().isEmpty(), "a ModelException carries at least one error");
        for (Diagnostic d : e.diagnostics()) {
            assertNotNull(d.message());
            assertFalse(d.message().isBlank(), () -> "empty message in " + d.format());
            assertEquals(file, d.file(), d::format);
            if (d.isError() && d.pos() != null) {
                assertTrue(d.line() >= 1 && d.column() >= 1, d::format);
                assertTrue(d.format().startsWith(file + ":" + d.line() + ":" + d.column() + ": error: " + d.message()),
                        d::format);
            }
        }
        assertEquals(e.diagnostics().stream().map(Diagnostic::format).collect(Collectors.joining("\n")),
                e.getMessage());
    }

    private static Diagnostic onlyError(ModelException e) {
        assertEquals(1, e.errors().size(), () -> "exactly one error expected, got:\n" + e.getMessage());
        return e.errors().get(0);
    }

    private static void assertError(Diagnostic d, String message, int line, int column) {
        assertTrue(d.isError(), d::format);
        assertTrue(d.message().contains(message), () -> "expected a message containing \"" + message + "\", got: "
                + d.format());
        assertEquals(line, d.line(), () -> "line of " + d.format());
        assertEquals(column, d.column(), () -> "column of " + d.format());
        assertTrue(d.format().startsWith(d.file() + ":" + line + ":" + column + ": error: "), d::format);
    }

    private static void assertInLabel(Diagnostic d, String template, String kind, int columnInLabel) {
        assertEquals(template, d.template(), () -> "template of " + d.format());
        assertEquals(kind, d.labelKind(), () -> "label kind of " + d.format());
        assertEquals(columnInLabel, d.pos().columnInFragment(), () -> "column inside the label of " + d.format());
    }

    private static XmlModel xml() {
        return new XmlModel();
    }

    /**
     * A minimal Uppaal XML model: globals, one template P with parameters, local declarations, locations A
     * (id0, with an invariant label) and B (id1), an initial location and one edge A -> B with all four
     * labels, and the system section. Every part stands on a line of its own, so positions are fixed:
     *
     * <pre>
     * line  3  global declaration   content from column 14
     * line  6  parameter            column 12
     * line  7  local declaration    column 14
     * line  8  invariant of A       column 58
     * line 10  init (replaceable)
     * line 11  the transition tag   column 1
     * line 14  select               column 22
     * line 15  guard                column 21
     * line 16  synchronisation      column 31
     * line 17  assignment           column 26
     * line 20  system               column 9
     * </pre>
     *
     * Empty labels are ignored by the reader, so the defaults form a correct model.
     */
    private static final class XmlModel {
        private String global = "clock x; chan a; int i;";
        private String parameters = "";
        private String local = "";
        private String invariant = "";
        private String init = "<init ref=\"id0\"/>";
        private String target = "id1";
        private String select = "";
        private String guard = "";
        private String sync = "";
        private String assign = "";
        private String system = "system P;";

        XmlModel global(String s) {
            global = s;
            return this;
        }

        XmlModel parameters(String s) {
            parameters = s;
            return this;
        }

        XmlModel local(String s) {
            local = s;
            return this;
        }

        XmlModel invariant(String s) {
            invariant = s;
            return this;
        }

        XmlModel init(String s) {
            init = s;
            return this;
        }

        XmlModel target(String s) {
            target = s;
            return this;
        }

        XmlModel select(String s) {
            select = s;
            return this;
        }

        XmlModel guard(String s) {
            guard = s;
            return this;
        }

        XmlModel sync(String s) {
            sync = s;
            return this;
        }

        XmlModel assign(String s) {
            assign = s;
            return this;
        }

        XmlModel system(String s) {
            system = s;
            return this;
        }

        String text() {
            return String.join("\n",
                    "<?xml version=\"1.0\" encoding=\"utf-8\"?>",
                    "<nta>",
                    "<declaration>" + global + "</declaration>",
                    "<template>",
                    "<name>P</name>",
                    "<parameter>" + parameters + "</parameter>",
                    "<declaration>" + local + "</declaration>",
                    "<location id=\"id0\"><name>A</name><label kind=\"invariant\">" + invariant + "</label></location>",
                    "<location id=\"id1\"><name>B</name></location>",
                    init,
                    "<transition>",
                    "<source ref=\"id0\"/>",
                    "<target ref=\"" + target + "\"/>",
                    "<label kind=\"select\">" + select + "</label>",
                    "<label kind=\"guard\">" + guard + "</label>",
                    "<label kind=\"synchronisation\">" + sync + "</label>",
                    "<label kind=\"assignment\">" + assign + "</label>",
                    "</transition>",
                    "</template>",
                    "<system>" + system + "</system>",
                    "</nta>") + "\n";
        }
    }
}
