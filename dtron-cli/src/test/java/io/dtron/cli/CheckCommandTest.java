package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class CheckCommandTest {
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");

    private record Run(int exit, String out, String err) {
    }

    private static Run dtron(String... args) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int exit = DtronCommand.run(args, new PrintWriter(out), new PrintWriter(err));
        return new Run(exit, out.toString(), err.toString());
    }

    @Test
    void summarisesAModelWithItsTronInterface() {
        Path tron = SHARED.resolve("tron");
        Run r = dtron("check", tron.resolve("LightContr.xml").toString(), "--interface",
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
        Run r = dtron("check", bad.toString(), SHARED.resolve("uppaal-examples/fischer.xml").toString());
        assertEquals(1, r.exit());
        assertTrue(r.err().contains(bad + ": 2 errors"), r.err());
        assertTrue(r.err().contains(bad + ":3:53: error: a guard is a conjunction of clock bounds"), r.err());
        assertTrue(r.err().contains(bad + ":3:80: error: unknown name 'j'"), r.err());
        assertTrue(r.out().contains("fischer.xml: ok"), "the other model is still checked: " + r.out());
        assertFalse(r.err().contains("Exception") || r.err().contains("\tat "), "no stack trace: " + r.err());
    }

    @Test
    void aMissingFileIsAnErrorWithoutStackTrace() {
        Run r = dtron("check", "does/not/exist.xml");
        assertEquals(1, r.exit());
        assertTrue(r.err().contains("does/not/exist.xml: error: no such file"), r.err());
        assertFalse(r.err().contains("Exception"), r.err());
    }

    @Test
    void badUsageExitsWithOneAndSaysWhyAndWhereTheHelpIs() {
        Run unknown = dtron("check", "--frobnicate", "x.xml");
        assertEquals(1, unknown.exit());
        assertTrue(unknown.err().contains("Unknown option: '--frobnicate'"), unknown.err());
        assertEquals("dtron check: Unknown option: '--frobnicate'" + System.lineSeparator() + "see 'dtron check --help'"
                + System.lineSeparator(), unknown.err(), "the reason and where the help is, not the whole usage");
        Run root = dtron("--frobnicate");
        assertEquals(1, root.exit());
        assertTrue(root.err().endsWith("see 'dtron --help'" + System.lineSeparator()), root.err());
        assertEquals(1, dtron("check").exit(), "a model is required");
        Run twoWithInterface = dtron("check", "a.xml", "b.xml", "--interface", "x.trn");
        assertEquals(1, twoWithInterface.exit());
        assertTrue(twoWithInterface.err().contains("--interface applies to one model"), twoWithInterface.err());
        assertEquals(1, dtron().exit(), "no subcommand prints usage");
    }

    @Test
    void helpAndVersion() {
        Run help = dtron("check", "--help");
        assertEquals(0, help.exit());
        assertTrue(help.out().contains("--interface=FILE.trn"), help.out());
        Run version = dtron("--version");
        assertEquals(0, version.exit());
        assertTrue(version.out().startsWith("dtron "), version.out());
    }

    @Test
    void quietPrintsNothingForGoodModels() {
        Run r = dtron("check", "-q", SHARED.resolve("uppaal-examples/bridge.xml").toString());
        assertEquals(0, r.exit());
        assertEquals("", r.out());
    }
}
