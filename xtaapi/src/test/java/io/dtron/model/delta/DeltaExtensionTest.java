package io.dtron.model.delta;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import io.dtron.model.delta.DeltaExtension.Delay;
import io.dtron.model.delta.DeltaExtension.Result;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;

class DeltaExtensionTest {
    private static final int P_PLUS_T = 12;

    /**
     * A two-port system: the server takes i_req and i_stop at port 1 and answers o_resp at port 2 within a bound;
     * the client is the environment. Written as the Uppaal editor writes XML: {@code >} escaped too.
     */
    static final String TWO_PORTS = """
            <?xml version="1.0" encoding="utf-8"?>
            <nta>
            \t<declaration>// Two ports: requests in at port 1, responses out at port 2.
            const int P = 10;
            const int T = 2;
            chan i_req, i_stop, o_resp;
            int n;</declaration>
            \t<template>
            \t\t<name>Server</name>
            \t\t<declaration>clock y, z;</declaration>
            \t\t<location id="id0" x="0" y="0"><name>Idle</name></location>
            \t\t<location id="id1" x="100" y="0"><name>Busy</name>
            \t\t\t<label kind="invariant" x="90" y="20">y &lt;= P + T</label></location>
            \t\t<init ref="id0"/>
            \t\t<transition><source ref="id0"/><target ref="id1"/>
            \t\t\t<label kind="guard" x="40" y="-40">z &gt;= 3</label>
            \t\t\t<label kind="synchronisation" x="40" y="-20">i_req?</label>
            \t\t\t<label kind="assignment" x="40" y="0">y = 0</label></transition>
            \t\t<transition><source ref="id1"/><target ref="id0"/>
            \t\t\t<!-- the answer: a lower bound written as a constant expression, and a clock difference -->
            \t\t\t<label kind="guard" x="40" y="40">y &gt;= P - T &amp;&amp; y - z &lt;= 50</label>
            \t\t\t<label kind="synchronisation" x="40" y="60">o_resp!</label></transition>
            \t\t<transition><source ref="id1"/><target ref="id1"/>
            \t\t\t<label kind="guard" x="140" y="0">y &lt;= n &amp;&amp; n &lt; 3</label>
            \t\t\t<label kind="synchronisation" x="140" y="20">i_stop?</label></transition>
            \t</template>
            \t<template>
            \t\t<name>Client</name>
            \t\t<declaration>clock c;</declaration>
            \t\t<location id="id2" x="0" y="0"><name>Ready</name></location>
            \t\t<location id="id3" x="100" y="0"><name>Waiting</name>
            \t\t\t<label kind="invariant" x="90" y="20">c &lt;= 50</label></location>
            \t\t<init ref="id2"/>
            \t\t<transition><source ref="id2"/><target ref="id3"/>
            \t\t\t<label kind="guard" x="40" y="-40">c &gt; 1</label>
            \t\t\t<label kind="synchronisation" x="40" y="-20">i_req!</label>
            \t\t\t<label kind="assignment" x="40" y="0">c = 0</label></transition>
            \t\t<transition><source ref="id3"/><target ref="id2"/>
            \t\t\t<label kind="guard" x="40" y="40">c &lt; 40</label>
            \t\t\t<label kind="synchronisation" x="40" y="60">o_resp?</label></transition>
            \t\t<transition><source ref="id3"/><target ref="id3"/>
            \t\t\t<label kind="guard" x="140" y="0">c == 7</label>
            \t\t\t<label kind="synchronisation" x="140" y="20">i_stop!</label></transition>
            \t\t<transition><source ref="id2"/><target ref="id2"/>
            \t\t\t<label kind="guard" x="-40" y="0">c &gt;= 5</label></transition>
            \t</template>
            \t<system>system Server, Client;</system>
            </nta>
            """;

    /**
     * req 2500..5200, stop 100..400 (inputs, hull 100..5200), resp 1200..2900 (output), in units of 1000 us:
     * an i_req edge widens lower bounds by floor(3700) = 3 and upper ones by ceil(8100) = 9; an o_resp edge by
     * floor(100 + 1200) = 1 and ceil(5200 + 2900) = 9; an i_stop edge by floor(1300) = 1 and ceil(3300) = 4.
     */
    static final Map<String, Delay> DELAYS = Map.of("req", new Delay(2500, 5200), "stop", new Delay(100, 400),
            "resp", new Delay(1200, 2900));

    private static Result extend(String name, String text, Map<String, Delay> delays) throws ModelException {
        Network network = ModelLoader.load(name, text);
        return DeltaExtension.extend(network, text, TestInterface.fromNames(network), delays, 1000, "a test");
    }

    @Test
    void widensTheBoundsOfObservableEdgesInPlaceAndKeepsTheRestByteForByte() throws ModelException {
        Result r = extend("two-ports.xml", TWO_PORTS, DELAYS);
        String expected = TWO_PORTS
                .replace(">z &gt;= 3<", ">z &gt;= 3 + 3<")
                .replace(">y &lt;= P + T<", ">y &lt;= (P + T) + 9<")
                .replace(">y &gt;= P - T &amp;&amp; y - z &lt;= 50<", ">y &gt;= (P - T) + 1 &amp;&amp; y - z &lt;= 50<")
                .replace(">c &gt; 1<", ">c &gt; 1 + 3<")
                .replace(">c &lt; 40<", ">c &lt; 40 + 9<")
                .replace(">c &lt;= 50<", ">c &lt;= 50 + 9<")
                .replace(">c == 7<", ">(c &gt;= 7 + 1 &amp;&amp; c &lt;= 7 + 4)<");
        int noteStart = r.text().indexOf("<declaration>") + "<declaration>".length();
        int noteEnd = r.text().indexOf("// Two ports:");
        String note = r.text().substring(noteStart, noteEnd);
        assertTrue(note.startsWith("// Delta-extended by dtron delta"), note);
        assertEquals(expected, r.text().substring(0, noteStart) + r.text().substring(noteEnd),
                "only the widened labels and the note differ");
        assertEquals(7, r.changes().size(), r.changes().toString());
        assertTrue(note.contains("input req 2500..5200 us (2..6 units)"), note);
        assertTrue(note.contains("output resp 1200..2900 us (1..3 units)"), note);
        assertTrue(note.contains("Widened 7 bounds (at the lines of the model before this comment):"), note);
        assertTrue(note.contains("Server: location Busy, invariant (o_resp!, i_stop?): y &lt;= P + T  -&gt;  "
                + "y &lt;= (P + T) + 9"), note);
        assertTrue(note.contains("y - z &lt;= 50: a clock difference is not widened"), note);
        assertTrue(note.contains("y &lt;= n: the bound is not a constant expression"), note);
        assertTrue(r.warnings().isEmpty(), r.warnings().toString());
    }

    @Test
    void theWidenedModelLoadsWithTheExpectedBounds() throws ModelException {
        Network before = ModelLoader.load("two-ports.xml", TWO_PORTS);
        Network after = ModelLoader.load("two-ports-delta.xml", extend("two-ports.xml", TWO_PORTS, DELAYS).text());
        assertEquals(bound(before, "Server", 0, 0) + 3, bound(after, "Server", 0, 0), "z >= 3 on i_req?");
        assertEquals(bound(before, "Server", 1, 0) + 1, bound(after, "Server", 1, 0), "y >= P - T on o_resp!");
        assertEquals(50, bound(after, "Server", 1, 1), "the clock difference is left");
        assertEquals(bound(before, "Client", 0, 0) + 3, bound(after, "Client", 0, 0), "c > 1 on i_req!");
        assertEquals(40 + 9, bound(after, "Client", 1, 0), "c < 40 on o_resp?");
        assertEquals(7 + 1, bound(after, "Client", 2, 0), "c == 7 on i_stop!, lower");
        assertEquals(7 + 4, bound(after, "Client", 2, 1), "c == 7 on i_stop!, upper");
        assertEquals(5, bound(after, "Client", 3, 0), "an edge without synchronisation is left");
        assertEquals(P_PLUS_T + 9, invariantBound(after, "Server", "Busy"));
        assertEquals(50 + 9, invariantBound(after, "Client", "Waiting"));
        assertEquals(0, invariantBound(after, "Client", "Ready"), "no invariant");
    }

    /** The constant of the {@code k}-th clock comparison of edge {@code edge}'s guard, in the order written. */
    private static int bound(Network n, String process, int edge, int k) {
        Edge e = n.process(process).orElseThrow().edges().get(edge);
        return constants(e.guard()).get(k);
    }

    private static int invariantBound(Network n, String process, String location) {
        Location l = n.process(process).orElseThrow().location(location);
        return l.invariant() == null ? 0 : constants(l.invariant()).get(0);
    }

    private static List<Integer> constants(Expression e) {
        if (e instanceof Expression.Binary b && (b.op() == Expression.Operator.AND
                || b.op() == Expression.Operator.OR)) {
            List<Integer> all = new ArrayList<>(constants(b.left()));
            all.addAll(constants(b.right()));
            return all;
        }
        if (e instanceof Expression.Binary b && b.right() instanceof Expression.Constant c) {
            return List.of(c.value());
        }
        if (e instanceof Expression.Binary b && b.left() instanceof Expression.Constant c) {
            return List.of(c.value());
        }
        return List.of();
    }

    @Test
    void xtaTextIsWidenedTheSameWayWithTheNoteAtTheTop() throws ModelException {
        String xta = """
                // Two ports, as text.
                const int P = 10, T = 2;
                chan i_req, o_resp;
                process Server() {
                  clock y;
                  state Idle, Busy { y <= (P + T) };
                  init Idle;
                  trans Idle -> Busy { sync i_req?; assign y = 0; },
                        Busy -> Idle { guard 2 <= y && y >= (P - T); sync o_resp!; };
                }
                system Server;
                """;
        Result r = extend("two-ports.xta", xta, Map.of("req", new Delay(2500, 5200), "resp", new Delay(1200, 2900)));
        String body = r.text().substring(r.text().indexOf("// Two ports, as text."));
        assertEquals(xta.replace("y <= (P + T) }", "y <= (P + T) + 9 }")
                .replace("2 <= y && y >= (P - T);", "2 + 3 <= y && y >= (P - T) + 3;"), body);
        assertTrue(r.text().startsWith("// Delta-extended by dtron delta (DTRON thesis, section 3.5) with a test.\n"),
                r.text());
        Process server = ModelLoader.load("out.xta", r.text()).process("Server").orElseThrow();
        assertEquals(List.of(5, 11), constants(server.edges().get(1).guard()));
        assertEquals(List.of(21), constants(server.location("Busy").invariant()));
    }

    @Test
    void windowsLineEndsAndCdataLabelsAreKept() throws ModelException {
        String crlf = TWO_PORTS.replace("\n", "\r\n").replace("<label kind=\"guard\" x=\"140\" y=\"0\">c == 7</label>",
                "<label kind=\"guard\" x=\"140\" y=\"0\"><![CDATA[c == 7]]></label>");
        Result r = extend("crlf.xml", crlf, DELAYS);
        assertFalse(r.text().replace("\r\n", "").contains("\n"), "no lone line feed: " + r.text());
        assertTrue(r.text().contains(">y &lt;= (P + T) + 9<"), r.text());
        assertTrue(r.text().contains("<![CDATA[(c >= 7 + 1 && c <= 7 + 4)]]>"), "not escaped in CDATA: " + r.text());
        assertEquals(List.of(8, 11), constants(ModelLoader.load("out.xml", r.text()).process("Client").orElseThrow()
                .edges().get(2).guard()));
    }

    @Test
    void lowerWideningsThatRoundToZeroAreLeftAndSaid() throws ModelException {
        Result r = extend("two-ports.xml", TWO_PORTS, Map.of("resp", new Delay(300, 600)));
        assertTrue(r.left().stream().anyMatch(l -> l.text().equals("y >= P - T")
                && l.reason().equals("the lower bound's widening of 300 us rounds down to 0 time units")), r.left()
                .toString());
        assertTrue(r.changes().stream().anyMatch(c -> c.after().equals("y <= (P + T) + 1")), r.changes().toString());
        assertTrue(r.text().contains(">y &gt;= P - T &amp;&amp; y - z &lt;= 50<"), "left as written");
    }

    @Test
    void aLabelSharedByAnObservableAndAnInternalInstanceIsWidenedForBothWithAWarning() throws ModelException {
        String xta = """
                chan i_go, internal;
                process Relay(chan &c) {
                  clock x;
                  state A, B;
                  init A;
                  trans A -> B { guard x >= 4; sync c!; };
                }
                Outer = Relay(i_go);
                Inner = Relay(internal);
                process Sink() { state S; init S; trans S -> S { sync i_go?; }, S -> S { sync internal?; }; }
                system Outer, Inner, Sink;
                """;
        Result r = extend("relay.xta", xta, Map.of("go", new Delay(2000, 3000)));
        assertTrue(r.text().contains("guard x >= 4 + 2;"), r.text());
        assertEquals(1, r.warnings().size(), r.warnings().toString());
        assertTrue(r.warnings().get(0).contains("is widened for every process of template Relay, also for Inner, where it"
                + " belongs to no edge of an input or output"),
                r.warnings().get(0));
    }

    @Test
    void badRequestsAreRefusedWithTheReason() throws ModelException {
        Network network = ModelLoader.load("two-ports.xml", TWO_PORTS);
        TestInterface i = TestInterface.fromNames(network);
        IllegalArgumentException unknown = assertThrows(IllegalArgumentException.class, () -> DeltaExtension.extend(
                network, TWO_PORTS, i, Map.of("move", new Delay(1, 2)), 1000, "x"));
        assertEquals("'move' is no channel of the test interface (inputs: req, stop; outputs: resp)",
                unknown.getMessage());
        assertThrows(IllegalArgumentException.class, () -> new Delay(5, 4));
        assertThrows(IllegalArgumentException.class, () -> new Delay(-1, 4));
        assertThrows(IllegalArgumentException.class, () -> DeltaExtension.extend(network, TWO_PORTS, i, Map.of(), 1000,
                "x"));
        assertThrows(IllegalArgumentException.class, () -> DeltaExtension.extend(network, TWO_PORTS, i, DELAYS, 0,
                "x"));
        IllegalArgumentException other = assertThrows(IllegalArgumentException.class, () -> DeltaExtension.extend(
                network, TWO_PORTS.replace("z &gt;= 3", "z &gt;= 4"), i, DELAYS, 1000, "x"));
        assertTrue(other.getMessage().startsWith("the network was not loaded from this text"), other.getMessage());
    }

    @Test
    void encodesAsTheOriginalWithItsByteOrderMark() {
        byte[] withBom = {(byte) 0xef, (byte) 0xbb, (byte) 0xbf, '<', 'n', '/', '>'};
        assertArrayEquals(withBom, DeltaExtension.encodeLike("<n/>", withBom));
        String latin = "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?><nta>\u00e9</nta>";
        assertArrayEquals(latin.getBytes(StandardCharsets.ISO_8859_1), DeltaExtension.encodeLike(latin,
                latin.getBytes(StandardCharsets.ISO_8859_1)));
        // UTF-16 stays UTF-16 in its byte order, with its mark
        String utf16 = "<?xml version=\"1.0\" encoding=\"utf-16\"?><nta>\u00e9</nta>";
        byte[] body = utf16.getBytes(StandardCharsets.UTF_16LE);
        byte[] original = new byte[body.length + 2];
        original[0] = (byte) 0xff;
        original[1] = (byte) 0xfe;
        System.arraycopy(body, 0, original, 2, body.length);
        assertArrayEquals(original, DeltaExtension.encodeLike(utf16, original));
    }
}
