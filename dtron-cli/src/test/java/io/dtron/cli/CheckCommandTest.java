package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class CheckCommandTest {
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");

    @Test
    void summarisesAModelWithItsTronInterface() {
        Path tron = SHARED.resolve("tron");
        CommandRun r = CommandRun.of("check", tron.resolve("LightContr.xml").toString(), "--interface",
                tron.resolve("LightContr.trn").toString());
        assertEquals(0, r.exit(), r.err());
        assertTrue(r.out().contains("LightContr.xml: ok"), r.out());
        assertTrue(r.out().matches("(?s).*processes\\s+7 .*"), r.out());
        assertTrue(r.out().contains("grasp(), release()"), r.out());
        assertTrue(r.out().contains("level(adapLevel)"), r.out());
        assertTrue(r.out().contains("time unit 1000 us"), r.out());
    }

    @Test
    void reportsEveryErrorWithItsPositionAndExitsWithOne(@TempDir Path dir) throws IOException {
        Path bad = dir.resolve("bad.xta");
        Files.writeString(bad, """
                clock x;
                int i;
                process P() { state A; init A; trans A -> A { guard x != 3; }, A -> A { assign j = 1; }; }
                system P;
                """);
        CommandRun r = CommandRun.of("check", bad.toString(), SHARED.resolve("uppaal-examples/fischer.xml").toString());
        assertEquals(1, r.exit());
        assertTrue(r.err().contains(bad + ": 2 errors"), r.err());
        assertTrue(r.err().contains(bad + ":3:53: error: a guard is a conjunction of clock bounds"), r.err());
        assertTrue(r.err().contains(bad + ":3:80: error: unknown name 'j'"), r.err());
        assertTrue(r.out().contains("fischer.xml: ok"), "the other model is still checked: " + r.out());
        assertFalse(r.err().contains("Exception") || r.err().contains("\tat "), "no stack trace: " + r.err());
    }

    @Test
    void aQueryWithAnErrorIsReportedButTheModelIsOk(@TempDir Path dir) throws IOException {
        Path model = dir.resolve("q.xml");
        Files.writeString(model, """
                <nta><declaration>int n;</declaration>
                <template><name>P</name><location id="a"><name>A</name></location><init ref="a"/></template>
                <system>system P;</system>
                <queries><query><formula>Pr[&lt;=10](&lt;&gt; P.A)</formula></query>
                <query><formula>E[&lt;=10](max: n)</formula></query>
                <query><formula>A[] n &lt;</formula></query></queries>
                </nta>
                """);
        CommandRun r = CommandRun.of("check", model.toString());
        assertEquals(0, r.exit(), r.err());
        assertTrue(r.out().contains(model + ": ok"), r.out());
        assertTrue(r.out().matches("(?s).*queries\\s+3  \\(1 with errors; they do not stop the model from loading or"
                + " running\\).*"), r.out());
        assertTrue(r.out().contains(model + ":6:27: error: syntax error: an operand is missing after '<' (formula,"
                + " column 8)"), r.out());
    }

    @Test
    void aMissingFileIsAnErrorWithoutStackTrace() {
        CommandRun r = CommandRun.of("check", "does/not/exist.xml");
        assertEquals(1, r.exit());
        assertTrue(r.err().contains("does/not/exist.xml: error: no such file"), r.err());
        assertFalse(r.err().contains("Exception"), r.err());
    }

    @Test
    void badUsageExitsWithOneAndSaysWhyAndWhereTheHelpIs() {
        CommandRun unknown = CommandRun.of("check", "--frobnicate", "x.xml");
        assertEquals(1, unknown.exit());
        assertTrue(unknown.err().contains("Unknown option: '--frobnicate'"), unknown.err());
        assertEquals("dtron check: Unknown option: '--frobnicate'" + System.lineSeparator() + "see 'dtron check --help'"
                + System.lineSeparator(), unknown.err(), "the reason and where the help is, not the whole usage");
        CommandRun root = CommandRun.of("--frobnicate");
        assertEquals(1, root.exit());
        assertTrue(root.err().endsWith("see 'dtron --help'" + System.lineSeparator()), root.err());
        assertEquals(1, CommandRun.of("check").exit(), "a model is required");
        CommandRun twoWithInterface = CommandRun.of("check", "a.xml", "b.xml", "--interface", "x.trn");
        assertEquals(1, twoWithInterface.exit());
        assertTrue(twoWithInterface.err().contains("--interface applies to one model"), twoWithInterface.err());
        assertEquals(1, CommandRun.of().exit(), "no subcommand prints usage");
    }

    @Test
    void helpAndVersion() {
        CommandRun help = CommandRun.of("check", "--help");
        assertEquals(0, help.exit());
        assertTrue(help.out().contains("--interface=FILE.trn"), help.out());
        CommandRun version = CommandRun.of("--version");
        assertEquals(0, version.exit());
        assertTrue(version.out().startsWith("dtron "), version.out());
    }

    @Test
    void quietPrintsNothingForGoodModels() {
        CommandRun r = CommandRun.of("check", "-q", SHARED.resolve("uppaal-examples/bridge.xml").toString());
        assertEquals(0, r.exit());
        assertEquals("", r.out());
    }
}
