package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.Expression;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.testsupport.DocPage;
import java.io.File;
import java.io.IOException;
import java.net.URISyntaxException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class DeltaCommandTest {
    private static final Path TICKER = Path.of("..", "models", "src", "main", "resources", "io", "dtron", "models",
            "ticker.xml");

    /** Request at port 1 (input), response at port 2 (output) within RESP_MAX of it; a clock difference. */
    private static final String TWO_PORTS = """
            <?xml version="1.0" encoding="utf-8"?>
            <nta>
            \t<declaration>const int RESP_MIN = 2, RESP_MAX = 8;
            chan i_req, o_resp;</declaration>
            \t<template>
            \t\t<name>Port</name>
            \t\t<declaration>clock x, t;</declaration>
            \t\t<location id="id0"><name>Idle</name></location>
            \t\t<location id="id1"><name>Serving</name><label kind="invariant">x &lt;= RESP_MAX</label></location>
            \t\t<init ref="id0"/>
            \t\t<transition><source ref="id0"/><target ref="id1"/>
            \t\t\t<label kind="synchronisation">i_req?</label><label kind="assignment">x = 0</label></transition>
            \t\t<transition><source ref="id1"/><target ref="id0"/>
            \t\t\t<label kind="guard">x &gt;= RESP_MIN &amp;&amp; x - t &lt;= 100</label>
            \t\t\t<label kind="synchronisation">o_resp!</label></transition>
            \t</template>
            \t<template>
            \t\t<name>User</name>
            \t\t<declaration>clock u;</declaration>
            \t\t<location id="id2"><name>Idle</name></location>
            \t\t<location id="id3"><name>Asked</name></location>
            \t\t<init ref="id2"/>
            \t\t<transition><source ref="id2"/><target ref="id3"/>
            \t\t\t<label kind="guard">u &gt; 3</label><label kind="synchronisation">i_req!</label>
            \t\t\t<label kind="assignment">u = 0</label></transition>
            \t\t<transition><source ref="id3"/><target ref="id2"/>
            \t\t\t<label kind="guard">u &lt; 20</label><label kind="synchronisation">o_resp?</label></transition>
            \t</template>
            \t<system>system Port, User;</system>
            </nta>
            """;

    private static Path fixture(String name) throws URISyntaxException {
        return Path.of(DeltaCommandTest.class.getResource(name).toURI());
    }

    @Test
    void writesTheTickersDeltaModelFromARunsReport(@TempDir Path dir) throws Exception {
        Path out = dir.resolve("ticker-delta.xml");
        CommandRun r = CommandRun.of("delta", TICKER.toString(), "--delta-from",
                fixture("delta-report.json").toString(), "-o", out.toString());
        assertEquals(0, r.exit(), r.err());
        assertEquals("", r.err());
        assertTrue(r.out().contains("time unit 10000 us"), "the report's time unit: " + r.out());
        assertTrue(r.out().contains("input  reset 180..2400 us (0..1 units)"), r.out());
        assertTrue(r.out().contains("widened 1 bound:"), r.out());
        assertTrue(r.out().contains("Ticker: location Running, invariant (o_tick!, i_reset?): x <= P + T  ->  "
                + "x <= (P + T) + 1"), r.out());
        assertTrue(r.out().contains("x >= P - T: the lower bound's widening of 270 us rounds down to 0 time units"),
                r.out());
        String written = Files.readString(out);
        assertTrue(written.contains("<label kind=\"invariant\" x=\"-40\" y=\"16\">x &lt;= (P + T) + 1</label>"),
                written);
        assertTrue(written.contains("<label kind=\"guard\" x=\"80\" y=\"-48\">x &gt;= P - T</label>"), written);
        assertTrue(written.contains("// Delta-extended by dtron delta (DTRON thesis, section 3.5) with the delays of"
                + " delta-report.json (run 3f2a9c)."), written);
        Network network = ModelLoader.load(out);
        assertEquals(13, constant(network.process("Ticker").orElseThrow().location("Running").invariant()));
        CommandRun check = CommandRun.of("check", out.toString());
        assertEquals(0, check.exit(), check.err());

        Path renamed = Files.copy(TICKER, dir.resolve("clock.xml"));
        CommandRun other = CommandRun.of("delta", renamed.toString(), "--delta-from",
                fixture("delta-report.json").toString(), "-o", dir.resolve("clock-delta.xml").toString());
        assertEquals(0, other.exit(), other.err());
        assertTrue(other.err().contains("warning: " + fixture("delta-report.json") + " was measured with model"
                + " ticker.xml, not clock.xml"), other.err());
    }

    @Test
    void widensTheTwoPortSystemGivenOnTheCommandLine(@TempDir Path dir) throws Exception {
        Path model = dir.resolve("two-ports.xml");
        Files.writeString(model, TWO_PORTS);
        Path out = dir.resolve("two-ports-delta.xml");
        CommandRun r = CommandRun.of("delta", model.toString(), "--delta", "req=1500..2500", "--delta",
                "resp=700..1200", "--timeunit", "1000", "-o", out.toString());
        assertEquals(0, r.exit(), r.err());
        // i_req edges: lower + floor(1500 + 700 us) = 2, upper + ceil(2500 + 1200 us) = 4; o_resp edges the same
        String expected = TWO_PORTS
                .replace(">x &lt;= RESP_MAX<", ">x &lt;= RESP_MAX + 4<")
                .replace(">x &gt;= RESP_MIN &amp;&amp; x - t &lt;= 100<",
                        ">x &gt;= RESP_MIN + 2 &amp;&amp; x - t &lt;= 100<")
                .replace(">u &gt; 3<", ">u &gt; 3 + 2<")
                .replace(">u &lt; 20<", ">u &lt; 20 + 4<");
        String written = Files.readString(out);
        int note = written.indexOf("// Delta-extended");
        int noteEnd = written.indexOf("const int RESP_MIN");
        assertEquals(expected, written.substring(0, note) + written.substring(noteEnd), "the rest byte for byte");
        assertTrue(r.out().contains("widened 4 bounds:"), r.out());
        assertTrue(r.out().contains("x - t <= 100: a clock difference is not widened"), r.out());
        Network network = ModelLoader.load(out);
        assertEquals(12, constant(network.process("Port").orElseThrow().location("Serving").invariant()));
        assertEquals(0, CommandRun.of("check", out.toString()).exit());
    }

    @Test
    void anXtaModelWithATronInterfaceStaysXta(@TempDir Path dir) throws IOException {
        Path model = dir.resolve("lamp.xta");
        Files.writeString(model, """
                chan press, light;
                process Lamp() { clock x; state Off, On { x <= 5 }; init Off;
                  trans Off -> On { sync press?; assign x = 0; }, On -> Off { guard x > 1; sync light!; }; }
                process User() { state U; init U; trans U -> U { sync press!; }, U -> U { sync light?; }; }
                system Lamp, User;
                """);
        Path trn = dir.resolve("lamp.trn");
        Files.writeString(trn, "input press(); output light(); precision 500; timeout 100;\n");
        Path out = dir.resolve("lamp-delta.xta");
        CommandRun r = CommandRun.of("delta", model.toString(), "--interface", trn.toString(), "--delta",
                "press=0..400", "--delta", "light=600..900", "-o", out.toString());
        assertEquals(0, r.exit(), r.err());
        assertTrue(r.out().contains("time unit 500 us"), "the interface file's precision: " + r.out());
        String written = Files.readString(out);
        // light! edge: lower + floor(0 + 600 / 500) = 1, the invariant of On + ceil((400 + 900) / 500) = 3
        assertTrue(written.contains("state Off, On { x <= 5 + 3 };"), written);
        assertTrue(written.contains("guard x > 1 + 1;"), written);
        assertTrue(written.startsWith("// Delta-extended by dtron delta"), written);
        assertEquals(0, CommandRun.of("check", out.toString(), "--interface", trn.toString()).exit());
    }

    @Test
    void refusesBadRequestsOnOneLineAndLosesNothing(@TempDir Path dir) throws Exception {
        Path model = dir.resolve("two-ports.xml");
        Files.writeString(model, TWO_PORTS);
        Path out = dir.resolve("out.xml");
        String m = model.toString();
        String o = out.toString();
        refused("--delta move=1..2: unknown channel 'move': the model's inputs are req, its outputs resp",
                "delta", m, "--delta", "move=1..2", "-o", o);
        refused("--delta i_req=1..2: unknown channel 'i_req' (name it 'req', its name on the bus, without i_/o_): the"
                + " model's inputs are req, its outputs resp", "delta", m, "--delta", "i_req=1..2", "-o", o);
        refused("--delta req=9..2: LOW is above HIGH", "delta", m, "--delta", "req=9..2", "-o", o);
        refused("--delta req=-1..2: expected CHANNEL=LOW..HIGH, LOW and HIGH whole numbers of microseconds, at least"
                + " 0, e.g. move=200..1500", "delta", m, "--delta", "req=-1..2", "-o", o);
        refused("--delta req=1..2: channel req is given twice", "delta", m, "--delta", "req=1..2", "--delta",
                "req=1..2", "-o", o);
        refused("give the delays: --delta CHANNEL=LOW..HIGH ... or --delta-from REPORT.json", "delta", m, "-o", o);
        refused("give the delays either with --delta or with --delta-from, not both", "delta", m, "--delta",
                "req=1..2", "--delta-from", "r.json", "-o", o);
        refused("--timeunit must be a positive number of microseconds, not 0", "delta", m, "--delta", "req=1..2",
                "--timeunit", "0", "-o", o);
        Path notJson = dir.resolve("not.json");
        Files.writeString(notJson, "{\"timeUnitMicros\": 1000, \"channels\": [],}");
        refused(notJson + " is not a delay report of dtron run --delta-report: line 1, column 41: expected a key in"
                + " double quotes", "delta", m, "--delta-from", notJson.toString(), "-o", o);
        Path wrongShape = dir.resolve("shape.json");
        Files.writeString(wrongShape, "{\"timeUnitMicros\": 1000, \"channels\": [{\"channel\": \"req\", \"direction\":"
                + " \"in\", \"count\": 1, \"lowMicros\": 1, \"highMicros\": 2}]}");
        refused(wrongShape + " is not a delay report of dtron run --delta-report: channel 'req': direction must be"
                + " \"input\" or \"output\", not \"in\"", "delta", m, "--delta-from", wrongShape.toString(), "-o", o);
        Path crossed = dir.resolve("crossed.json");
        Files.writeString(crossed, "{\"timeUnitMicros\": 1000, \"channels\": [{\"channel\": \"req\", \"direction\":"
                + " \"output\", \"count\": 1, \"lowMicros\": 1, \"highMicros\": 2}]}");
        refused(crossed + ": channel 'req' is an output in the report but an input of " + model, "delta", m,
                "--delta-from", crossed.toString(), "-o", o);
        Path unmeasured = dir.resolve("unmeasured.json");
        Files.writeString(unmeasured, "{\"timeUnitMicros\": 1000, \"channels\": [{\"channel\": \"req\", \"direction\":"
                + " \"input\", \"count\": 0, \"lowMicros\": 0, \"highMicros\": 0}]}");
        refused(unmeasured + " measured no channel (every count is 0): nothing to widen", "delta", m, "--delta-from",
                unmeasured.toString(), "-o", o);
        refused(dir.resolve("out.xta") + ": the Delta-extended model is written in the model's own format, Uppaal XML;"
                + " name it .xml", "delta", m, "--delta", "req=1..2", "-o", dir.resolve("out.xta").toString());
        refused(dir.resolve("none.xml") + ": no such file", "delta", dir.resolve("none.xml").toString(), "--delta",
                "req=1..2", "-o", o);
        assertFalse(Files.exists(out), "nothing written");

        Files.writeString(out, "keep me");
        refused(o + " exists; give --force to overwrite it", "delta", m, "--delta", "req=1..2", "-o", o);
        assertEquals("keep me", Files.readString(out));
        assertEquals(0, CommandRun.of("delta", m, "--delta", "req=1000..2000", "-o", o, "--force").exit());
        assertTrue(Files.readString(out).contains("x &lt;= RESP_MAX + 2"));
        byte[] before = Files.readAllBytes(model);
        refused(m + " is the model itself; write the Delta-extended model to another file", "delta", m, "--delta",
                "req=1..2", "-o", m, "--force");
        assertArrayEquals(before, Files.readAllBytes(model));
        try (var files = Files.list(dir)) {
            assertTrue(files.noneMatch(f -> f.getFileName().toString().endsWith(".tmp")), "no temporary file left");
        }
    }

    @Test
    void aModelErrorIsListedWithItsPlace(@TempDir Path dir) throws IOException {
        Path bad = dir.resolve("bad.xta");
        Files.writeString(bad, "chan i_a;\nprocess P() { state A; init A; trans A -> A { guard y > 1; sync i_a?; };"
                + " }\nsystem P;\n");
        CommandRun r = CommandRun.of("delta", bad.toString(), "--delta", "a=1..2", "-o", dir.resolve("o.xta")
                .toString());
        assertEquals(1, r.exit());
        assertTrue(r.err().contains(bad + ": 1 error"), r.err());
        assertTrue(r.err().contains("unknown name 'y'"), r.err());
        assertFalse(r.err().contains("Exception") || r.err().contains("\tat "), r.err());
        assertFalse(Files.exists(dir.resolve("o.xta")));
    }

    @Test
    void theExampleOfTheUserGuideIsWhatTheCommandDoes(@TempDir Path dir) throws IOException {
        DocPage page = DocPage.read("cli.md");
        String session = page.blocksStartingWith("$ java -jar dtron.jar delta").get(0).code();
        String[] lines = session.split("\n", -1);
        String command = (lines[0] + lines[1]).replace("\\", " ").replace("$ java -jar dtron.jar", "").trim();
        Files.copy(TICKER, dir.resolve("ticker.xml"));
        String[] args = command.split("\\s+");
        for (int i = 0; i < args.length; i++) {
            if (args[i].endsWith(".xml")) {
                args[i] = dir.resolve(args[i]).toString();
            }
        }
        CommandRun r = CommandRun.of(args);
        assertEquals(0, r.exit(), r.err());
        String expected = String.join("\n", List.of(lines).subList(2, lines.length));
        assertEquals(expected, r.out().replace(dir + File.separator, "").replace(System.lineSeparator(), "\n"));
        String written = Files.readString(dir.resolve("ticker-delta.xml"));
        String labels = page.blockAfter("Before and after, the labels in the XML").code();
        String[] label = labels.split("\n");
        assertTrue(Files.readString(TICKER).contains(label[0].trim()) && Files.readString(TICKER)
                .contains(label[1].trim()), labels);
        assertTrue(written.contains(label[3].trim()) && written.contains(label[4].trim()), labels);
        String comment = page.blockAfter("and the global declarations start with the comment").code();
        String shown = comment.substring(0, comment.indexOf("...")).replace("&lt;", "<").replace("&gt;", ">");
        assertTrue(written.replace("&lt;", "<").replace("&gt;", ">").contains(shown), shown);
    }

    @Test
    void helpListsTheOptions() {
        CommandRun help = CommandRun.of("delta", "--help");
        assertEquals(0, help.exit());
        for (String option : new String[] {"--delta=CHANNEL=LOW..HIGH", "--delta-from=REPORT.json", "--timeunit=US",
                "--output=OUT", "--force", "--interface=FILE.trn"}) {
            assertTrue(help.out().contains(option), option + " in " + help.out());
        }
        assertTrue(CommandRun.of("--help").out().contains("delta"), "listed among the commands");
    }

    private static void refused(String message, String... args) {
        CommandRun r = CommandRun.of(args);
        assertEquals(1, r.exit(), r.out() + r.err());
        assertEquals("dtron delta: " + message + System.lineSeparator(), r.err(), "one line");
    }

    private static int constant(Expression e) {
        return ((Expression.Constant) ((Expression.Binary) e).right()).value();
    }
}
