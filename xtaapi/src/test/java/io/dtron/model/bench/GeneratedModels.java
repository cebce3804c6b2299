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
