package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class CheckTestabilityTest {
    private static final String LAMP = """
            clock x, y;
            chan i_press, o_light;
            process User() { state idle; init idle;
                trans idle -> idle { guard y >= 1; sync i_press!; assign y = 0; }, idle -> idle { sync o_light?; }; }
            process Lamp() { state off, on { x <= 5 }; init off;
                trans off -> on { sync i_press?; assign x = 0; }, on -> off { guard x >= 2; sync o_light!; }%s; }
            system User, Lamp;
            """;

    @Test
    void aTestableModelPassesEveryCheckWithExitCodeZero(@TempDir Path dir) throws IOException {
        Path lamp = dir.resolve("lamp.xta");
        Files.writeString(lamp, LAMP.formatted(", on -> on { sync i_press?; }"));
        CommandRun r = CommandRun.of("check", "--testability", lamp.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("testability ("), r.out());
        for (String check : new String[] {"output observability", "input enabledness", "connectedness",
                "environment coverage", "strong responsiveness", "time-lock freedom", "Zeno freedom"}) {
            assertTrue(r.out().matches("(?s).*\\n    " + check + " +ok\\n.*"), check + ": " + r.out());
        }
    }

    @Test
    void aFailedCheckPrintsItsProblemWithATraceAndExitsWithTwo(@TempDir Path dir) throws IOException {
        Path lamp = dir.resolve("lamp.xta");
        Files.writeString(lamp, LAMP.formatted(""));
        CommandRun r = CommandRun.of("check", "--testability", lamp.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().matches("(?s).*\\n    input enabledness +1 problem\\n.*"), r.out());
        assertTrue(r.out().contains("- the implementation does not accept the input press in Lamp.on"), r.out());
        assertTrue(r.out().contains("- the implementation does not accept the input press in Lamp.on when x<=5\n"),
                r.out());
        assertTrue(r.out().contains("state 1: Lamp.on, CanonicalTester.offering; x<=5"), "the trace: " + r.out());
        assertFalse(r.err().contains("Exception"), r.err());
    }

    @Test
    void aCycleOfInternalMovesIsPrintedAsALasso(@TempDir Path dir) throws IOException {
        Path lamp = dir.resolve("lamp.xta");
        Files.writeString(lamp, LAMP.formatted(
                ", on -> on { sync i_press?; }, on -> on { guard x >= 1; assign x = 0; }"));
        CommandRun r = CommandRun.of("check", "--testability", lamp.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().matches("(?s).*\\n    strong responsiveness +1 problem\\n.*"), r.out());
        assertTrue(r.out().contains("- the implementation can move for ever without an input or an output: a cycle of"
                + " internal moves from Lamp.on"), r.out());
        assertTrue(r.out().matches("(?s).*\\n +and then a cycle back to state \\d\\n.*"), r.out());
        assertTrue(r.out().matches("(?s).*\\n    Zeno freedom +ok\\n.*"), "each round takes a unit: " + r.out());
    }

    @Test
    void anInputVariableWithTooManyValuesIsNoted(@TempDir Path dir) throws IOException {
        Path lamp = dir.resolve("lamp.xta");
        Files.writeString(lamp, LAMP.formatted(", on -> on { sync i_press?; }").replace("chan i_press, o_light;",
                "chan i_press, o_light; int i_press_level;"));
        CommandRun r = CommandRun.of("check", "--testability", lamp.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("(partly: input press is offered with i_press_level as it is (initially 0): its"
                + " 65536 values are too many to offer each)"), r.out());
    }

    @Test
    void aModelThatDoesNotSplitIsReportedNotCrashed(@TempDir Path dir) throws IOException {
        Path both = dir.resolve("both.xta");
        // P sends the input and receives it itself: it would be on both sides
        Files.writeString(both, """
                chan i_a;
                process P() { state s, t; init s; trans s -> t { sync i_a!; }, t -> s { sync i_a?; }; }
                system P;
                """);
        CommandRun r = CommandRun.of("check", "--testability", both.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().matches("(?s).*\\n    output observability +1 problem\\n.*"), r.out());
        assertTrue(r.out().contains("(not checked: the model does not split into environment and implementation)"),
                r.out());
    }
}
