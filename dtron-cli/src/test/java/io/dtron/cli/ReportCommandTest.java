package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron run --report} and {@code --live}, and {@code dtron report TRACE -o FILE.html}: one page from a run and
 * from its trace; clear one-line errors for bad traces and options.
 */
class ReportCommandTest {
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

    @Test
    void theReportOfARunAndTheReportOfItsTraceAreTheSamePage(@TempDir Path dir) throws Exception {
        Path model = Files.writeString(dir.resolve("ticker.xta"), TICKER);
        Path trace = dir.resolve("run.jsonl");
        Path page = dir.resolve("run.html");
        CommandRun run = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName() + ":slow",
                "--virtual-time", "--seed", "7", "--timeout", "300", "--trace", trace.toString(), "--report",
                page.toString());
        assertEquals(2, run.exit(), run.out() + run.err());
        List<String> lines = run.out().lines().toList();
        assertTrue(lines.get(lines.size() - 1).equals("dtron run: report written to " + page), run.out());
        String html = Files.readString(page);
        assertTrue(html.contains("\"verdict\":{\"verdict\":\"FAILED\",\"explanation\":\"no output came by t=12.000"),
                "the verdict and its explanation");
        assertTrue(html.contains("\"name\":\"Ticker\",\"auto\":true"), "a textual model is laid out automatically");
        assertTrue(html.contains("\"coverage\":{\"summary\":\"coverage: "), "the coverage");
        assertFalse(html.contains("src=\"http") || html.contains("href=\"http"), "nothing fetched from a network");
        String traced = Files.readString(trace);
        assertTrue(traced.contains("{\"kind\":\"due\",\"t_us\":0,\"until_us\":12000}"),
                "the deadline of the first tick");
        assertTrue(traced.lines().anyMatch(l -> l.startsWith("{\"kind\":\"coverage\",\"coverage\":{")), "coverage");

        Path again = dir.resolve("again.html");
        CommandRun report = CommandRun.of("report", trace.toString(), "-o", again.toString());
        assertEquals(0, report.exit(), report.out() + report.err());
        assertEquals("", report.err());
        assertTrue(report.out().strip().matches("dtron report: \\d+ inputs and outputs of .* written to .*"),
                report.out());
        assertArrayEquals(Files.readAllBytes(page), Files.readAllBytes(again), "the same page, byte for byte");
    }

    @Test
    void aModelOfAnotherRunIsRefusedByItsFingerprintNotDrawnAsIfItWereTheRunsOne(@TempDir Path dir)
            throws Exception {
        Path model = Files.writeString(dir.resolve("ticker.xta"), TICKER);
        Path trace = dir.resolve("run.jsonl");
        CommandRun run = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "7", "--timeout", "100", "--trace", trace.toString());
        assertEquals(0, run.exit(), run.out() + run.err());
        // the same text under another name is the run's model; a ticker with one more location is not
        Path copy = Files.writeString(dir.resolve("copy.xta"), TICKER);
        assertEquals(0, CommandRun.of("report", trace.toString(), "--model", copy.toString(), "-o",
                dir.resolve("copy.html").toString()).exit());
        Path other = Files.writeString(dir.resolve("other.xta"), TICKER.replace("state Running { x <= P + T };",
                "state Running { x <= P + T }, Spare;"));
        Path page = dir.resolve("other.html");
        CommandRun r = CommandRun.of("report", trace.toString(), "--model", other.toString(), "-o", page.toString());
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.err().matches("dtron report: " + java.util.regex.Pattern.quote(other + " is not the model of the"
                + " run of " + trace + ": the run's model was " + model + ", fingerprint ") + "[0-9a-f]{16}, not"
                + " [0-9a-f]{16}\\R"), r.err());
        assertFalse(Files.exists(page), "no page of the wrong model");
        // the model the trace names, changed since the run, is refused the same way, with where to give the right one
        Files.writeString(model, TICKER.replace("state Running { x <= P + T };", "state Running { x <= P + T }, Spare;"));
        CommandRun changed = CommandRun.of("report", trace.toString(), "-o", page.toString());
        assertEquals(1, changed.exit(), changed.out() + changed.err());
        assertTrue(changed.err().strip().endsWith("; give the run's model with --model"), changed.err());
    }

    @Test
    void eachOutputCarriesTheWindowTheModelAllowedItInFromTheRunToItsTraceAndPage(@TempDir Path dir)
            throws Exception {
        // the ticker's model allows a tick 8 to 12 units after the last tick or reset
        Path model = Files.writeString(dir.resolve("ticker.xta"), TICKER);
        Path trace = dir.resolve("run.jsonl");
        Path page = dir.resolve("run.html");
        CommandRun run = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "7", "--timeout", "100", "--trace", trace.toString(), "--report",
                page.toString());
        assertEquals(0, run.exit(), run.out() + run.err());
        java.util.regex.Pattern event = java.util.regex.Pattern.compile(
                "\\{\"kind\":\"(input|output)\",\"t_us\":(\\d+),.*?(?:,\"allowed_from_us\":(-?\\d+),"
                        + "\"allowed_until_us\":(-?\\d+))?}");
        long last = 0;
        int outputs = 0;
        String html = Files.readString(page);
        for (String line : Files.readAllLines(trace)) {
            java.util.regex.Matcher m = event.matcher(line);
            if (!m.matches()) {
                continue;
            }
            long at = Long.parseLong(m.group(2));
            if (m.group(1).equals("output")) {
                outputs++;
                long until = last + 12_000 >= 100_000 ? -1 : last + 12_000;
                assertEquals(last + 8_000 + " " + until, m.group(3) + " " + m.group(4), line);
                assertTrue(java.util.regex.Pattern.compile("\\[1," + at + ",\"tick\",\"seq=\\d+\",-?\\d+,"
                        + (last + 8_000) + "," + until + "]").matcher(html).find(), "the window beside the tick at "
                        + at);
            }
            last = at;
        }
        assertTrue(outputs > 0, "the ticker ticked");
        Path again = dir.resolve("again.html");
        assertEquals(0, CommandRun.of("report", trace.toString(), "-o", again.toString()).exit());
        assertArrayEquals(Files.readAllBytes(page), Files.readAllBytes(again), "the same page, byte for byte");
    }

    @Test
    void aTraceWhoseModelIsGoneStillGivesItsRunSayingSo(@TempDir Path dir) throws Exception {
        Path trace = Files.writeString(dir.resolve("t.jsonl"), """
                {"kind":"start","seed":1,"model":"gone.xta","timeunit_us":1000,"timeout":50,"virtual_time":true}
                {"kind":"input","t_us":1000,"channel":"reset","values":{}}
                {"kind":"bus","channel":"reset"}
                {"kind":"output","t_us":2000,"channel":"tick","values":{"seq":1}}
                {"kind":"output","t_us":9000,"channel":"tick","values":{"seq":2},"allowed_from_us":8000,"allowed_until_us":-1}
                {"kind":"verdict","t_us":50000,"verdict":"PASSED","seed":1,"inputs":1,"outputs":1,"explanation":"ok"}
                """);
        Path page = dir.resolve("t.html");
        CommandRun r = CommandRun.of("report", trace.toString(), "-o", page.toString());
        assertEquals(0, r.exit(), r.err());
        assertEquals("dtron report: warning: the model gone.xta was not found (as given, or beside the trace): give"
                + " it with --model; the report shows the run without the model", r.err().strip());
        String html = Files.readString(page);
        // a trace from before outputs carried their windows (the first tick) is read as well
        assertTrue(html.contains("\"events\":[[0,1000,\"reset\",\"\",-1,-1,-1],\n[1,2000,\"tick\",\"seq=1\",-1,-1,-1],"
                + "\n[1,9000,\"tick\",\"seq=2\",-1,8000,-1]]"), html);
    }

    @Test
    void aBadTraceIsOneLineNamingWhereAndWhy(@TempDir Path dir) throws Exception {
        Path page = dir.resolve("p.html");
        CommandRun missing = CommandRun.of("report", dir.resolve("none.jsonl").toString(), "-o", page.toString());
        assertEquals(1, missing.exit());
        assertEquals("dtron report: " + dir.resolve("none.jsonl") + ": no such file", missing.err().strip());
        Path notJson = Files.writeString(dir.resolve("a.jsonl"), """
                {"kind":"start","seed":1,"model":"gone.xta","timeunit_us":1000,"timeout":50,"virtual_time":true}
                {"kind":"input","t_us":
                """);
        CommandRun bad = CommandRun.of("report", notJson.toString(), "-o", page.toString());
        assertEquals(1, bad.exit());
        assertTrue(bad.err().endsWith("dtron report: " + notJson + " line 2: not JSON: column 24: the text ends where a"
                + " value was expected\n"), bad.err());
        Path noStart = Files.writeString(dir.resolve("b.jsonl"), "{\"kind\":\"input\",\"t_us\":1}\n");
        CommandRun headless = CommandRun.of("report", noStart.toString(), "-o", page.toString());
        assertEquals(1, headless.exit());
        assertEquals("dtron report: " + noStart + " line 1: not a trace of dtron run: it does not begin with its start"
                + " line", headless.err().strip());
        Path badValue = Files.writeString(dir.resolve("c.jsonl"), """
                {"kind":"start","seed":1,"model":"gone.xta","timeunit_us":1000,"timeout":50,"virtual_time":true}
                {"kind":"output","t_us":5,"channel":"tick","values":{"seq":"one"}}
                """);
        CommandRun value = CommandRun.of("report", badValue.toString(), "-o", page.toString());
        assertEquals(1, value.exit());
        assertTrue(value.err().endsWith(badValue + " line 2: the value of seq is not an int\n"), value.err());
        for (CommandRun r : List.of(missing, bad, headless, value)) {
            assertFalse(r.err().contains("\tat "), r.err());
            assertFalse(Files.exists(page));
        }
    }

    @Test
    void theLiveViewsOptionsAreCheckedBeforeTheRun(@TempDir Path dir) throws Exception {
        String model = Files.writeString(dir.resolve("ticker.xta"), TICKER).toString();
        CommandRun port = CommandRun.of("run", model, "--sut", TickerForTests.class.getName(), "--virtual-time",
                "--live", "70000");
        assertEquals(1, port.exit());
        assertTrue(port.err().startsWith("dtron run: --live takes a port of 0 to 65535 (0: any free port): 70000"),
                port.err());
        CommandRun bind = CommandRun.of("run", model, "--sut", TickerForTests.class.getName(), "--virtual-time",
                "--bind", "127.0.0.1");
        assertEquals(1, bind.exit());
        assertTrue(bind.err().contains("leave it out (or give --live PORT: the live view listens there)"), bind.err());
        CommandRun folder = CommandRun.of("run", model, "--sut", TickerForTests.class.getName(), "--virtual-time",
                "--report", dir.resolve("no/such/folder/r.html").toString());
        assertEquals(1, folder.exit());
        assertTrue(folder.err().startsWith("dtron run: --report " + dir.resolve("no/such/folder/r.html")
                + ": there is no folder " + dir.resolve("no/such/folder") + " to write it in"), folder.err());
        CommandRun mutants = CommandRun.of("mutants", model, "--report", "x.html");
        assertEquals(1, mutants.exit());
        assertTrue(mutants.err().startsWith("dtron mutants: --report is an option of a run against one system under"
                + " test"), mutants.err());
        CommandRun tron = CommandRun.of("run", model, "--backend", "tron", "--report", "x.html");
        assertEquals(1, tron.exit());
        assertTrue(tron.err().startsWith("dtron run: --report and --live show DTRON's engine's run"), tron.err());
    }

    @Test
    void aLiveRunSaysWhereToWatchItOnLoopback(@TempDir Path dir) throws Exception {
        String model = Files.writeString(dir.resolve("ticker.xta"), TICKER).toString();
        CommandRun r = CommandRun.of("run", model, "--sut", TickerForTests.class.getName(), "--virtual-time",
                "--seed", "3", "--timeout", "100", "--live", "0");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().lines().anyMatch(l -> l.matches("dtron run: live view at http://127\\.0\\.0\\.1:\\d+/")),
                r.out());
        CommandRun bound = CommandRun.of("run", model, "--sut", TickerForTests.class.getName(), "--virtual-time",
                "--seed", "3", "--timeout", "100", "--live", "0", "--bind", "127.0.0.2");
        assertEquals(0, bound.exit(), bound.out() + bound.err());
        assertTrue(bound.out().lines().anyMatch(l -> l.matches("dtron run: live view at http://127\\.0\\.0\\.2:\\d+/")),
                bound.out());
    }
}
