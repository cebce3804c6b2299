package io.dtron.xta;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.xta.ast.Decl;
import io.dtron.xta.ast.Expr;
import io.dtron.xta.ast.Initializer;
import io.dtron.xta.ast.Nta;
import java.util.Collections;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * Nesting past the front end's limit is a model error with its place, not a stack overflow; long sections are
 * parsed item by item with the same result and the same errors as at once; deeply nested XML is read.
 */
class LimitsAndLargeTextsTest {
    private static final String LIMIT = "nested deeper than the limit of 1000 levels";

    private static String xml(String declarations, String guard) {
        return "<nta><declaration>" + declarations + "</declaration>\n<template><name>P</name>"
                + "<location id=\"a\"/><init ref=\"a\"/>\n<transition><source ref=\"a\"/><target ref=\"a\"/>"
                + "<label kind=\"guard\">" + guard + "</label></transition></template>\n"
                + "<system>system P;</system></nta>";
    }

    private static Diagnostic onlyError(Parsed<Nta> parsed) {
        assertEquals(1, parsed.diagnostics().size(), parsed.diagnostics().toString());
        Diagnostic d = parsed.diagnostics().get(0);
        assertTrue(d.isError(), d.format());
        return d;
    }

    @Test
    void parenthesesFourThousandDeepAreAnErrorAtTheLevelPastTheLimit() {
        String decl = "int x = " + "(".repeat(4000) + "1" + ")".repeat(4000) + ";";
        Diagnostic d = onlyError(ModelSyntax.parseXta("deep.xta", "\n" + decl + "\nsystem P;"));
        // the outermost expression, at the first '(' (column 9), is level 1: level 1001 starts at the 1001st '('
        assertEquals("deep.xta:2:1009: error: expression " + LIMIT, d.format());
        Diagnostic inXml = onlyError(ModelSyntax.parseXml("deep.xml", xml(decl, "true")));
        assertEquals("deep.xml:1:1027: error: expression " + LIMIT + " (declaration, column 1009)", inXml.format());
        Diagnostic inGuard = onlyError(ModelSyntax.parseXml("deep.xml", xml("", "(".repeat(4000) + "true"
                + ")".repeat(4000))));
        assertEquals("guard", inGuard.labelKind());
        assertTrue(inGuard.message().equals("expression " + LIMIT), inGuard.format());
    }

    @Test
    void nestingUpToTheLimitParses() {
        String decl = "int x = " + "(".repeat(999) + "1" + ")".repeat(999) + ";\nint y = "
                + String.join(" + ", Collections.nCopies(1000, "1")) + ";";
        Parsed<Nta> parsed = ModelSyntax.parseXml("ok.xml", xml(decl, "!".repeat(998) + "true"));
        assertFalse(parsed.hasErrors(), parsed.diagnostics().toString());
        Decl.Variable y = assertInstanceOf(Decl.Variable.class, parsed.value().declarations().get(1));
        assertInstanceOf(Expr.Binary.class, assertInstanceOf(Initializer.Single.class, y.init()).value());
    }

    @Test
    void aLongOperatorChainIsAsDeepAsItIsLong() {
        // the parser reads a chain in a loop, but its tree is as deep as it is long
        String sum = String.join(" + ", Collections.nCopies(5000, "1"));
        Diagnostic d = onlyError(ModelSyntax.parseXta("sum.xta", "int x = " + sum + ";\nsystem P;"));
        assertEquals("expression " + LIMIT, d.message());
        assertEquals("+", d.pos().text(), "at the operator of the level past the limit");
        // level k is the k-th '+' from the end: level 1001 is the 3999th '+', after the 3999th "1"
        assertEquals(1, d.line());
        assertEquals("int x = ".length() + 4 * (3999 - 1) + 3, d.column());
    }

    @Test
    void statementsInitialisersAndTypesHaveTheSameLimit() {
        Diagnostic blocks = onlyError(ModelSyntax.parseXta("s.xta", "void f() " + "{".repeat(3000) + "}".repeat(3000)
                + "\nsystem P;"));
        assertEquals("statements " + LIMIT, blocks.message());
        Diagnostic ifs = onlyError(ModelSyntax.parseXta("s.xta", "int a; void f() { " + "if (a) ".repeat(3000)
                + "a = 1; }\nsystem P;"));
        assertEquals("statements " + LIMIT, ifs.message());
        Diagnostic braces = onlyError(ModelSyntax.parseXta("i.xta", "int a[1] = " + "{".repeat(3000) + "1"
                + "}".repeat(3000) + ";\nsystem P;"));
        assertEquals("initialiser braces " + LIMIT, braces.message());
        Diagnostic structs = onlyError(ModelSyntax.parseXta("t.xta", "typedef " + "struct { ".repeat(3000) + "int a;"
                + " } b;".repeat(3000) + "\nsystem P;"));
        assertEquals("types " + LIMIT, structs.message());
    }

    @Test
    void deeplyNestedXmlElementsAreSkipped() {
        int depth = 100_000;
        String deep = "<nta><declaration>int x;</declaration>" + "<a>".repeat(depth) + "</a>".repeat(depth)
                + "<template><name>P</name><location id=\"l\">" + "<b>".repeat(depth) + "</b>".repeat(depth)
                + "</location><init ref=\"l\"/></template><system>system P;</system></nta>";
        Parsed<Nta> parsed = ModelSyntax.parseXml("deep.xml", deep);
        assertFalse(parsed.hasErrors(), parsed.diagnostics().toString());
        assertEquals("element <a> is not part of an Uppaal model and is ignored", parsed.diagnostics().get(0).message());
        assertEquals(1, parsed.value().templates().get(0).locations().size());
    }

    @Test
    void aLongSectionParsedItemByItemGivesTheSameDeclarationsAndPositions() {
        StringBuilder decls = new StringBuilder();
        for (int i = 0; i < 2000; i++) {
            decls.append("const int c").append(i).append(" = ").append(i).append(";\n")
                    .append("int f").append(i).append("(int a) { return a &lt; c").append(i).append(" ? a : 0; }\n");
        }
        Parsed<Nta> parsed = ModelSyntax.parseXml("long.xml", xml(decls.toString(), "c1999 &gt;= 0"));
        assertFalse(parsed.hasErrors(), parsed.diagnostics().toString());
        List<Decl> all = parsed.value().declarations();
        assertEquals(4001, all.size(), "2,000 constants, 2,000 functions and the template");
        Decl.Function last = assertInstanceOf(Decl.Function.class, all.get(3999));
        assertEquals("f1999", last.name());
        assertEquals(4000, last.pos().line());
        assertEquals(5, last.pos().column());
    }

    @Test
    void syntaxErrorsInALongSectionAreAllReported() {
        StringBuilder text = new StringBuilder();
        for (int i = 0; i < 500; i++) {
            text.append("int v").append(i).append(i == 100 || i == 400 ? " = ;" : ";").append('\n');
        }
        text.append("process P() { state A; init A; }\nsystem P;\n");
        Parsed<Nta> parsed = ModelSyntax.parseXta("errors.xta", text.toString());
        List<Integer> lines = parsed.diagnostics().stream().map(Diagnostic::line).toList();
        assertEquals(List.of(101, 401), lines, parsed.diagnostics().toString());
    }

    @Test
    void aSystemSectionWithProcessesAndInstantiationsParsesItemByItem() {
        Parsed<Nta> parsed = ModelSyntax.parseXta("sys.xta", """
                int n;
                process P(int k) { state A; init A; }
                P1 = P(1);
                P2 = P(2);
                system P1 < P2;
                """);
        assertFalse(parsed.hasErrors(), parsed.diagnostics().toString());
        assertEquals(4, parsed.value().declarations().size());
        assertEquals(2, parsed.value().system().levels().size());
    }
}
