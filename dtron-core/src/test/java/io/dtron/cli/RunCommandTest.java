package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class RunCommandTest {
    private static final String TICKER = """
            const int P = 10; const int T = 2;
            chan i_reset, o_tick;
            int[0,999] o_tick_seq;
            process Ticker() { clock x; state Running { x <= P + T }; init Running;
                trans Running -> Running { guard x >= P - T; sync o_tick!; assign o_tick_seq = (o_tick_seq + 1) % 1000, x = 0; },
                      Running -> Running { sync i_reset?; assign x = 0, o_tick_seq = 0; }; }
            process Env() { clock e; state Watching; init Watching;
                trans Watching -> Watching { guard e >= 25; sync i_reset!; assign e = 0; },
                      Watching -> Watching { sync o_tick?; }; }
            system Ticker, Env;
            """;

    @TempDir
    static Path dir;
    private static Path model;

    @BeforeAll
    static void writeModel() throws IOException {
        model = dir.resolve("ticker.xta");
        Files.writeString(model, TICKER);
    }

    private record Run(int exit, String out, String err) {
    }

    private static Run dtron(String... args) {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int exit = DtronCommand.run(args, new PrintWriter(out), new PrintWriter(err));
        return new Run(exit, out.toString(), err.toString());
    }

    @Test
    void aCorrectSystemPassesWithExitCodeZero() {
        Run r = dtron("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time", "--seed", "7",
                "--timeout", "300");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("seed 7"), r.out());
        assertTrue(r.out().contains("PASSED: the timeout of 300 time units was reached"), r.out());
        assertTrue(r.out().matches("(?s).*statistics: 7 PASSED \\d+ \\d+ 300000 .*"), r.out());
    }

    @Test
    void aFaultySystemFailsWithExitCodeTwoAndAnExplanation() {
        Run r = dtron("run", model.toString(), "--sut", TickerForTests.class.getName() + ":slow", "--virtual-time",
                "--seed", "7", "--timeout", "300");
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("FAILED: no output came by t=12.000"), r.out());
        assertTrue(r.out().contains("tick between t=8.000 and t=12.000 (Ticker: Running -> Running)"), r.out());
    }

    @Test
    void theSameSeedGivesTheSameTraceByteForByte() throws IOException {
        Path a = dir.resolve("a.jsonl");
        Path b = dir.resolve("b.jsonl");
        for (Path trace : List.of(a, b)) {
            Run r = dtron("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time", "--seed",
                    "42", "--timeout", "500", "--trace", trace.toString());
            assertEquals(0, r.exit(), r.out() + r.err());
        }
        assertArrayEquals(Files.readAllBytes(a), Files.readAllBytes(b));
        List<String> lines = Files.readAllLines(a);
        assertTrue(lines.get(0).startsWith("{\"kind\":\"start\",\"seed\":42,"), lines.get(0));
        assertTrue(lines.stream().anyMatch(l -> l.startsWith("{\"kind\":\"input\",\"t_us\":")), "inputs are traced");
        assertTrue(lines.stream().anyMatch(l -> l.contains("\"channel\":\"tick\",\"values\":{\"seq\":1}")),
                "outputs are traced with their values");
        assertTrue(lines.get(lines.size() - 1).startsWith("{\"kind\":\"verdict\",\"t_us\":500000,\"verdict\":\"PASSED\""),
                lines.get(lines.size() - 1));
        Path c = dir.resolve("c.jsonl");
        dtron("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time", "--seed", "43",
                "--timeout", "500", "--trace", c.toString());
        assertFalse(java.util.Arrays.equals(Files.readAllBytes(a), Files.readAllBytes(c)), "another seed, another run");
    }

    @Test
    void usageErrorsExitWithOneAndSayWhy() {
        Run noClass = dtron("run", model.toString(), "--sut", "no.such.Sut", "--virtual-time");
        assertEquals(1, noClass.exit());
        assertTrue(noClass.err().contains("no class no.such.Sut on the classpath"), noClass.err());
        Run notAdapter = dtron("run", model.toString(), "--sut", "java.lang.String", "--virtual-time");
        assertEquals(1, notAdapter.exit());
        assertTrue(notAdapter.err().contains("does not implement io.dtron.engine.Adapter"), notAdapter.err());
        Run variant = dtron("run", model.toString(), "--sut", TickerForTests.class.getName() + ":weird");
        assertEquals(1, variant.exit());
        assertTrue(variant.err().contains("unknown variant 'weird' (correct, slow)"), variant.err());
        Run policy = dtron("run", model.toString(), "--sut", TickerForTests.class.getName(), "--delay-policy", "soon");
        assertEquals(1, policy.exit());
        assertTrue(policy.err().contains("unknown delay policy 'soon'"), policy.err());
        Run missingSut = dtron("run", model.toString());
        assertEquals(1, missingSut.exit());
        assertTrue(missingSut.err().contains("Missing required option: '--sut=CLASS[:VARIANT]'"), missingSut.err());
        Run badTimeout = dtron("run", model.toString(), "--sut", TickerForTests.class.getName(), "--timeout", "0");
        assertEquals(1, badTimeout.exit());
        assertTrue(badTimeout.err().contains("the timeout must be a positive number"), badTimeout.err());
        assertFalse((noClass.err() + variant.err() + policy.err()).contains("\tat "), "no stack traces");
    }
}
