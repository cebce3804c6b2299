package io.dtron.model.bench;

/** Generates large Uppaal XML models for the load benchmark and its sanity test. */
public final class GeneratedModels {
    private GeneratedModels() {
    }

    /**
     * A model whose system line expands one template over {@code processes} values of its free parameter:
     * each process has a clock, local variables, a function, four locations and six edges.
     */
    public static String manyProcesses(int processes) {
        StringBuilder sb = header();
        sb.append("<declaration>const int N = ").append(processes).append(";\n")
                .append("typedef int[0,N-1] id_t;\nchan req[id_t], ack[id_t];\nbroadcast chan tick;\n")
                .append("int[0,N] granted;\nbool busy[id_t];\n</declaration>\n");
        sb.append("<template><name>Worker</name><parameter>const id_t id</parameter>\n")
                .append("<declaration>clock x;\nint[0,10] count;\nint next(int v) { return (v + 1) % 10; }</declaration>\n");
        location(sb, "a", "Idle", "x &lt;= 10");
        location(sb, "b", "Asking", "x &lt;= 5");
        location(sb, "c", "Working", "x &lt;= 20");
        location(sb, "d", "Done", null);
        sb.append("<init ref=\"a\"/>\n");
        edge(sb, "a", "b", "x &gt;= 2 &amp;&amp; !busy[id]", "req[id]!", "x = 0, busy[id] = true");
        edge(sb, "b", "c", "x &lt;= 5", "ack[id]?", "x = 0, count = next(count)");
        edge(sb, "c", "d", "x &gt;= 10 &amp;&amp; count &lt; 10", null, "busy[id] = false");
        edge(sb, "d", "a", null, "tick?", "x = 0");
        edge(sb, "c", "a", "x == 20", null, "x = 0, busy[id] = false");
        edge(sb, "b", "a", "x == 5", null, "x = 0, busy[id] = false");
        sb.append("</template>\n");
        sb.append("<template><name>Server</name><declaration>clock y;</declaration>\n");
        location(sb, "s", "Serve", "y &lt;= 1");
        sb.append("<init ref=\"s\"/>\n");
        sb.append("<transition><source ref=\"s\"/><target ref=\"s\"/><label kind=\"select\">i : id_t</label>")
                .append("<label kind=\"synchronisation\">req[i]?</label><label kind=\"assignment\">granted = i</label>")
                .append("</transition>\n");
        sb.append("<transition><source ref=\"s\"/><target ref=\"s\"/><label kind=\"select\">i : id_t</label>")
                .append("<label kind=\"guard\">granted == i</label><label kind=\"synchronisation\">ack[i]!</label>")
                .append("</transition>\n");
        edge(sb, "s", "s", "y == 1", "tick!", "y = 0");
        sb.append("</template>\n<system>system Worker, Server;</system>\n</nta>\n");
        return sb.toString();
    }

    /** A model of at least {@code bytes} characters (at most one template more): many templates with labelled edges. */
    public static String largeFile(int bytes) {
        StringBuilder sb = header();
        sb.append("<declaration>const int K = 7;\nint shared[16];\nchan c[16];\n</declaration>\n");
        StringBuilder system = new StringBuilder("system ");
        int t = 0;
        while (sb.length() < bytes) {
            String name = "T" + t;
            sb.append("<template><name>").append(name).append("</name>\n<declaration>clock x;\nint[0,100] v;\n")
                    .append("int f(int a) { int r = 0; for (i : int[0,3]) { r += a * i; } return r % 100; }")
                    .append("</declaration>\n");
            for (int l = 0; l < 20; l++) {
                location(sb, name + "_" + l, "L" + l, "x &lt;= " + (10 + l));
            }
            sb.append("<init ref=\"").append(name).append("_0\"/>\n");
            for (int l = 0; l < 20; l++) {
                int next = (l + 1) % 20;
                edge(sb, name + "_" + l, name + "_" + next, "x &gt;= " + l + " &amp;&amp; v &lt; 100 &amp;&amp; shared["
                        + (l % 16) + "] &lt;= K", "c[" + (l % 16) + "]" + (l % 2 == 0 ? "!" : "?"),
                        "x = 0, v = f(v), shared[" + (l % 16) + "] = (shared[" + (l % 16) + "] + 1) % 8");
                edge(sb, name + "_" + l, name + "_0", "x == " + (10 + l), null, "x = 0, v = 0");
            }
            sb.append("</template>\n");
            system.append(t == 0 ? "" : ", ").append(name);
            t++;
        }
        sb.append("<system>").append(system).append(";</system>\n</nta>\n");
        return sb.toString();
    }

    /**
     * A model of at least {@code bytes} characters (at most one template more) as the Uppaal editor writes it:
     * global declarations with a struct, channel arrays and a function; templates with a parameter, local
     * clocks, variables and a function, 30 locations with names, invariants and drawing positions (some urgent
     * or committed) and 45 edges with select, guard, synchronisation, update and comment labels and nails; one
     * instantiation per template.
     */
    public static String editorFile(int bytes) {
        StringBuilder sb = header();
        sb.append("<declaration>// generated for the loader memory bench\nconst int N = 16;\nconst int K = 7;\n")
                .append("typedef int[0,N-1] id_t;\ntypedef struct { int[0,100] level; bool on; } cell_t;\n")
                .append("chan c[N];\nurgent chan u[N];\nbroadcast chan go;\nint[0,100] shared[N];\ncell_t cells[N];\n")
                .append("int clampLevel(int v) { if (v &lt; 0) return 0; else if (v &gt; 100) return 100; return v; }\n")
                .append("</declaration>\n");
        StringBuilder system = new StringBuilder();
        StringBuilder systemLine = new StringBuilder("system ");
        int t = 0;
        while (sb.length() + system.length() < bytes) {
            String name = "Station" + t;
            sb.append("<template>\n<name x=\"5\" y=\"5\">").append(name).append("</name>\n")
                    .append("<parameter>const id_t id</parameter>\n")
                    .append("<declaration>clock x, y;\nint[0,100] v;\nbool flag;\n")
                    .append("int step(int a) {\n    int r = 0;\n    for (i : int[0,3]) {\n        r += a * i;\n")
                    .append("    }\n    return clampLevel(r % 100);\n}</declaration>\n");
            for (int l = 0; l < 30; l++) {
                String id = "id" + (t * 30 + l);
                int x = (l % 6) * 170 - 400;
                int y = (l / 6) * 136 - 300;
                sb.append("<location id=\"").append(id).append("\" x=\"").append(x).append("\" y=\"").append(y)
                        .append("\">\n<name x=\"").append(x - 10).append("\" y=\"").append(y - 34).append("\">")
                        .append(l == 0 ? "Idle" : "Busy" + l).append("</name>\n");
                if (l % 3 != 2) {
                    sb.append("<label kind=\"invariant\" x=\"").append(x - 10).append("\" y=\"").append(y + 17)
                            .append("\">x &lt;= ").append(20 + l).append(" &amp;&amp; y &lt;= ").append(100 + l)
                            .append("</label>\n");
                }
                if (l % 10 == 5) {
                    sb.append("<urgent/>\n");
                } else if (l % 10 == 7) {
                    sb.append("<committed/>\n");
                }
                sb.append("</location>\n");
            }
            sb.append("<init ref=\"id").append(t * 30).append("\"/>\n");
            for (int e = 0; e < 45; e++) {
                int from = e % 30;
                int to = (e * 7 + 1) % 30;
                int x = (from % 6) * 170 - 315;
                int y = (from / 6) * 136 - 280;
                sb.append("<transition>\n<source ref=\"id").append(t * 30 + from).append("\"/>\n<target ref=\"id")
                        .append(t * 30 + to).append("\"/>\n");
                if (e % 5 == 0) {
                    label(sb, "select", x, y - 51, "j : id_t");
                }
                label(sb, "guard", x, y - 34, "x &gt;= " + (e % 20) + " &amp;&amp; v &lt; 100 &amp;&amp; shared[id] &lt;= K"
                        + (e % 5 == 0 ? " &amp;&amp; cells[j].on" : " &amp;&amp; !flag"));
                if (e % 3 == 0) {
                    label(sb, "synchronisation", x, y - 17, e % 5 == 0 ? "c[j]!" : "c[(id + 1) % N]?");
                } else if (e % 3 == 1 && (from % 10 == 5 || from % 10 == 7)) {
                    label(sb, "synchronisation", x, y - 17, "go!");
                }
                label(sb, "assignment", x, y, "x = 0, v = step(v), shared[id] = (shared[id] + 1) % 8,\n"
                        + "cells[id].level = clampLevel(cells[id].level + " + (e % 9) + "), flag = !flag");
                if (e % 4 == 0) {
                    label(sb, "comments", x, y + 17, "edge " + e + " of " + name + ": retries after a timeout");
                }
                sb.append("<nail x=\"").append(x + 20).append("\" y=\"").append(y + 40).append("\"/>\n")
                        .append("</transition>\n");
            }
            sb.append("</template>\n");
            system.append("P").append(t).append(" = ").append(name).append("(").append(t % 16).append(");\n");
            systemLine.append(t == 0 ? "" : ", ").append("P").append(t);
            t++;
        }
        sb.append("<system>").append(system).append(systemLine).append(";</system>\n</nta>\n");
        return sb.toString();
    }

    /**
     * A model of at least {@code bytes} characters whose bulk is one global declarations section: constant
     * tables, variables with initialisers, structs and functions with loops and branches; one small template uses
     * the last function.
     */
    public static String largeDeclarations(int bytes) {
        StringBuilder sb = header();
        sb.append("<declaration>const int N = 16;\ntypedef int[0,N-1] id_t;\n")
                .append("typedef struct { int[0,100] level; bool on; int[-5,5] trend; } cell_t;\n");
        int i = 0;
        while (sb.length() < bytes) {
            sb.append("// block ").append(i).append("\nconst int table").append(i).append("[8] = {")
                    .append(i % 7).append(", 1, 2, 3, 5, 8, 13, 21};\n")
                    .append("int[0,1000] counter").append(i).append(" = ").append(i % 1000).append(";\n")
                    .append("cell_t cell").append(i).append("[N];\n")
                    .append("int update").append(i).append("(int a, int b) {\n    int r = 0;\n")
                    .append("    for (k : int[0,7]) {\n        if (a &gt; table").append(i).append("[k]) {\n")
                    .append("            r += b * k;\n        } else {\n            r -= 1;\n        }\n    }\n")
                    .append("    while (r &lt; 0) {\n        r += 100;\n    }\n")
                    .append("    cell").append(i).append("[a % N].level = r % 101;\n")
                    .append("    return (r % 100 + counter").append(i).append(") % 1000;\n}\n");
            i++;
        }
        sb.append("</declaration>\n<template><name>User</name><declaration>clock x;</declaration>\n");
        location(sb, "a", "Idle", "x &lt;= 10");
        sb.append("<init ref=\"a\"/>\n");
        edge(sb, "a", "a", "x &gt;= 5", null, "x = 0, counter0 = update" + (i - 1) + "(counter0 % N, 3)");
        sb.append("</template>\n<system>system User;</system>\n</nta>\n");
        return sb.toString();
    }

    private static void label(StringBuilder sb, String kind, int x, int y, String text) {
        sb.append("<label kind=\"").append(kind).append("\" x=\"").append(x).append("\" y=\"").append(y).append("\">")
                .append(text).append("</label>\n");
    }

    private static StringBuilder header() {
        return new StringBuilder("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!DOCTYPE nta PUBLIC "
                + "'-//Uppaal Team//DTD Flat System 1.5//EN' 'http://www.it.uu.se/research/group/darts/uppaal/flat-1_5.dtd'>\n"
                + "<nta>\n");
    }

    private static void location(StringBuilder sb, String id, String name, String invariant) {
        sb.append("<location id=\"").append(id).append("\" x=\"0\" y=\"0\"><name>").append(name).append("</name>");
        if (invariant != null) {
            sb.append("<label kind=\"invariant\">").append(invariant).append("</label>");
        }
        sb.append("</location>\n");
    }

    private static void edge(StringBuilder sb, String from, String to, String guard, String sync, String update) {
        sb.append("<transition><source ref=\"").append(from).append("\"/><target ref=\"").append(to).append("\"/>");
        if (guard != null) {
            sb.append("<label kind=\"guard\">").append(guard).append("</label>");
        }
        if (sync != null) {
            sb.append("<label kind=\"synchronisation\">").append(sync).append("</label>");
        }
        if (update != null) {
            sb.append("<label kind=\"assignment\">").append(update).append("</label>");
        }
        sb.append("</transition>\n");
    }
}
