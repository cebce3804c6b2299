package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --replay} on traces that {@code dtron run --sut model} records in virtual time: correct runs
 * of the samples have no violation, faults seeded into a trace are found at their event (a missed deadline at the
 * deadline), {@code --continue} counts them, and lines that cannot be read are reported with file and line, counted,
 * and raise no alarm.
 */
class MonitorCommandTest {
    static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
    static final Path SERVER = Path.of("../dtron-engine/src/test/resources/io/dtron/engine/monitor/server.xta");
    static final Path TICKER = Path.of("../models/src/main/resources/io/dtron/models/ticker.xml");
    static final Path STREET = Path.of("../models/src/main/resources/io/dtron/models/streetlight/streetlight.xml");
    static final Path LAMP = SHARED.resolve("tron/LightContr.xml");
    static final Path LAMP_TRN = SHARED.resolve("tron/LightContr.trn");

    /** Records a run of {@code model} against its own implementation part in virtual time; the trace's lines. */
    static List<String> record(Path dir, Path model, long seed, long timeout, String... more) throws Exception {
        Path trace = dir.resolve("run-" + seed + ".jsonl");
        List<String> args = new ArrayList<>(List.of("run", model.toString(), "--sut", "model", "--virtual-time",
                "--seed", String.valueOf(seed), "--timeout", String.valueOf(timeout), "--trace", trace.toString()));
        args.addAll(List.of(more));
        CommandRun r = CommandRun.of(args.toArray(String[]::new));
        assertEquals(0, r.exit(), r.out() + r.err());
        return Files.readAllLines(trace, StandardCharsets.UTF_8);
    }

    static CommandRun monitor(Path dir, String name, List<String> lines, String... args) throws Exception {
        Path file = dir.resolve(name);
        Files.write(file, lines, StandardCharsets.UTF_8);
        List<String> all = new ArrayList<>(List.of("monitor"));
        all.addAll(List.of(args));
        all.addAll(List.of("--replay", file.toString()));
        CommandRun r = CommandRun.of(all.toArray(String[]::new));
        assertFalse(r.err().contains("\tat "), "no stack trace: " + r.err());
        return r;
    }

    /** {@link #monitor}, asserting its exit code and a text it printed. */
    static CommandRun expect(int exit, String printed, Path dir, String name, List<String> lines, String... args)
            throws Exception {
        CommandRun r = monitor(dir, name, lines, args);
        assertEquals(exit, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains(printed), r.out());
        return r;
    }

    /** The events of a trace as CSV lines: t_us,channel,name=value;... */
    static List<String> csv(List<String> trace) {
        List<String> out = new ArrayList<>(List.of("t_us,channel,values"));
        for (String line : trace) {
            Map<?, ?> m = (Map<?, ?>) Json.parse(line);
            if ("input".equals(m.get("kind")) || "output".equals(m.get("kind"))) {
                List<String> values = new ArrayList<>();
                ((Map<?, ?>) m.get("values")).forEach((k, v) -> values.add(k + "=" + v));
                out.add(m.get("t_us") + "," + m.get("channel") + "," + String.join(";", values));
            }
        }
        return out;
    }

    static int events(List<String> trace) {
        return (int) trace.stream().filter(l -> l.startsWith("{\"kind\":\"input\"") || l.startsWith("{\"kind\":\"output\""))
                .count();
    }

    /** The end of a recorded run: its verdict line's time, or its timeout when that comes first. */
    static long end(List<String> trace) {
        Map<?, ?> start = (Map<?, ?>) Json.parse(trace.get(0));
        long timeout = (Long) start.get("timeout") * (Long) start.get("timeunit_us");
        return trace.stream().map(l -> (Map<?, ?>) Json.parse(l)).filter(m -> "verdict".equals(m.get("kind")))
                .mapToLong(m -> Math.min((Long) m.get("t_us"), timeout)).findFirst().orElseThrow();
    }

    @Test
    void correctRunsOfTheSamplesReplayWithoutViolation(@TempDir Path dir) throws Exception {
        List<Object[]> samples = List.of(new Object[] {SERVER, 500L, new String[0], List.of("initial", "any")},
                new Object[] {TICKER, 500L, new String[0], List.of("initial", "any")},
                new Object[] {LAMP, 3000L, new String[] {"--interface", LAMP_TRN.toString()}, List.of("initial", "any")},
                new Object[] {STREET, 500L, new String[0], List.of("initial", "any")});
        for (Object[] s : samples) {
            Path model = (Path) s[0];
            String[] more = (String[]) s[2];
            for (long seed = 1; seed <= 3; seed++) {
                List<String> trace = record(dir, model, seed, (Long) s[1], more);
                int events = events(trace);
                assertTrue(events > 3, model + " seed " + seed + ": " + events + " events");
                for (Object from : (List<?>) s[3]) {
                    List<String> args = new ArrayList<>(List.of(model.toString(), "--from", from.toString()));
                    args.addAll(List.of(more));
                    CommandRun r = monitor(dir, "t.jsonl", trace, args.toArray(String[]::new));
                    assertEquals(0, r.exit(), r.out() + r.err());
                    assertTrue(r.out().contains("no violation, " + events + " events checked, 0 lines rejected"), r.out());
                    // a CSV does not say where the run ended: --end says it, as the JSON trace's verdict line
                    args.addAll(List.of("--end", Long.toString(end(trace))));
                    CommandRun c = monitor(dir, "t.csv", csv(trace), args.toArray(String[]::new));
                    assertEquals(0, c.exit(), c.out() + c.err());
                    assertTrue(c.out().contains("(CSV)"), c.out());
                }
            }
        }
    }

    @Test
    void aWrongValueSeededIntoATraceIsFoundAtItsEvent(@TempDir Path dir) throws Exception {
        List<String> trace = record(dir, LAMP, 2, 3000, "--interface", LAMP_TRN.toString());
        int k = -1;
        for (int i = 0; i < trace.size(); i++) {
            if (trace.get(i).startsWith("{\"kind\":\"output\"") && trace.get(i).contains("\"channel\":\"level\"")) {
                k = i; // the last output
            }
        }
        assertTrue(k > 0, "the run has an output");
        Map<?, ?> output = (Map<?, ?>) Json.parse(trace.get(k));
        long level = (Long) ((Map<?, ?>) output.get("values")).get("adapLevel");
        List<String> faulty = new ArrayList<>(trace);
        faulty.set(k, trace.get(k).replace("\"adapLevel\":" + level, "\"adapLevel\":" + (level + 7)));
        Path alarms = dir.resolve("alarms.jsonl");
        CommandRun r = monitor(dir, "f.jsonl", faulty, LAMP.toString(), "--interface", LAMP_TRN.toString(), "--alarms",
                alarms.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        long t = (Long) output.get("t_us");
        assertTrue(r.out().contains("violation 1 at t=" + String.format("%d.%03d", t / 1000, t % 1000) + ": level(adapLevel="
                + (level + 7) + ")"), r.out());
        assertTrue(r.out().contains("it allowed level with {adapLevel=" + level + "}"), r.out());
        List<String> lines = Files.readAllLines(alarms);
        assertEquals(1, lines.size());
        Map<?, ?> alarm = (Map<?, ?>) Json.parse(lines.get(0));
        assertEquals("wrong_values", alarm.get("reason"));
        assertEquals(t, alarm.get("t_us"));
        assertEquals("level", alarm.get("channel"));
    }

    @Test
    void aDroppedResponseIsFoundAtItsDeadline(@TempDir Path dir) throws Exception {
        List<String> trace = record(dir, SERVER, 4, 500);
        int resp = -1;
        for (int i = 0; i < trace.size() && resp < 0; i++) {
            if (trace.get(i).startsWith("{\"kind\":\"output\"")) {
                resp = i;
            }
        }
        long request = -1;
        for (int i = resp - 1; i >= 0 && request < 0; i--) {
            if (trace.get(i).startsWith("{\"kind\":\"input\"")) {
                request = (Long) ((Map<?, ?>) Json.parse(trace.get(i))).get("t_us");
            }
        }
        List<String> dropped = new ArrayList<>(trace);
        dropped.remove(resp);
        CommandRun r = monitor(dir, "d.jsonl", dropped, SERVER.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        long deadline = request + 3000;
        assertTrue(r.out().contains("violation 1 at t=" + String.format("%d.%03d", deadline / 1000, deadline % 1000)
                + ": no event by t=" + String.format("%d.%03d", deadline / 1000, deadline % 1000)), r.out());
        assertTrue(r.out().contains("the model could be in Server.Busy, Client.Waiting"), r.out());
        // the end of the run is a time too: a response dropped at the end is found at its deadline
        List<String> end = new ArrayList<>(List.of(trace.get(0), "{\"kind\":\"input\",\"t_us\":1000,\"channel\":\"req\","
                + "\"values\":{\"n\":1}}", "{\"kind\":\"verdict\",\"t_us\":9000,\"verdict\":\"PASSED\"}"));
        CommandRun e = monitor(dir, "e.jsonl", end, SERVER.toString());
        assertEquals(2, e.exit(), e.out() + e.err());
        assertTrue(e.out().contains("violation 1 at t=4.000: no event by t=4.000"), e.out());
        // the tester observed until its timeout, t=3 here, though its verdict came later: the deadline is after it
        List<String> timeout = new ArrayList<>(end);
        timeout.set(0, "{\"kind\":\"start\",\"seed\":1,\"model\":\"server.xta\",\"timeunit_us\":1000,\"timeout\":3,"
                + "\"virtual_time\":false}");
        CommandRun t = monitor(dir, "t.jsonl", timeout, SERVER.toString());
        assertEquals(0, t.exit(), t.out() + t.err());
    }

    @Test
    void aDeadlineAfterTheLastEventOfATraceWithoutAnEndIsNotJudgedButSaid(@TempDir Path dir) throws Exception {
        // a log that stops after a request: whether its response came by t=4 the log does not say
        List<String> log = List.of("t_us,channel,values", "1000,req,n=1");
        CommandRun r = monitor(dir, "open.csv", log, SERVER.toString());
        assertEquals(3, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("dtron monitor: the deadline at t=4.000 after the last event at t=1.000 was not"
                + " judged: the trace does not say when the run ended (give it with --end US)\n"), r.out());
        assertTrue(r.out().contains("dtron monitor: no violation, 1 event checked, 0 lines rejected, a deadline after"
                + " the last event not judged, in "), r.out());
        Path xml = dir.resolve("open.xml");
        monitor(dir, "open.csv", log, SERVER.toString(), "--junit", xml.toString());
        assertTrue(Files.readString(xml).contains("type=\"INCOMPLETE\""), Files.readString(xml));
        // a DTRON trace cut short (no verdict line) is such a trace too
        List<String> cut = List.of("{\"kind\":\"start\",\"seed\":1,\"model\":\"server.xta\",\"timeunit_us\":1000,"
                + "\"timeout\":50,\"virtual_time\":false}", "{\"kind\":\"input\",\"t_us\":1000,\"channel\":\"req\","
                + "\"values\":{\"n\":1}}");
        assertEquals(3, monitor(dir, "cut.jsonl", cut, SERVER.toString()).exit());
        // --end gives the run's end: the deadline before it is judged, missed
        expect(2, "violation 1 at t=4.000: no event by t=4.000", dir, "open.csv", log, SERVER.toString(), "--end",
                "9000");
        // an end before the deadline: nothing was due by then
        CommandRun early = expect(0, "no violation, 1 event checked, 0 lines rejected, in ", dir, "open.csv", log,
                SERVER.toString(), "--end", "3000");
        assertFalse(early.out().contains("not judged"), early.out());
        // a trace that ends answered has nothing pending
        assertEquals(0, monitor(dir, "done.csv", List.of("1000,req,n=1", "2500,resp,n=2"), SERVER.toString()).exit());
        // an event after --end is a rejected line; a bad --end a usage error
        CommandRun after = monitor(dir, "open.csv", log, SERVER.toString(), "--end", "500");
        assertEquals(3, after.exit(), after.out() + after.err());
        assertEquals(dir.resolve("open.csv") + ":2: the event at 1000 us comes after the run's end at 500 us (--end)",
                after.err().strip());
        CommandRun bad = monitor(dir, "open.csv", log, SERVER.toString(), "--end", "-1");
        assertEquals(1, bad.exit());
        assertTrue(bad.err().startsWith("dtron monitor: --end must be a time of the run"), bad.err());
    }

    @Test
    void continuingCountsTheViolations(@TempDir Path dir) throws Exception {
        List<String> trace = record(dir, SERVER, 5, 2000);
        List<String> faulty = new ArrayList<>();
        int changed = 0;
        int outputs = 0;
        for (String line : trace) {
            if (line.startsWith("{\"kind\":\"output\"") && changed < 3 && outputs++ % 2 == 0) {
                Map<?, ?> m = (Map<?, ?>) Json.parse(line);
                long n = (Long) ((Map<?, ?>) m.get("values")).get("n");
                line = line.replace("\"n\":" + n, "\"n\":" + (n + 5) % 10);
                changed++;
            }
            faulty.add(line);
        }
        assertEquals(3, changed, "three responses given a wrong value");
        Path alarms = dir.resolve("alarms.jsonl");
        CommandRun r = monitor(dir, "c.jsonl", faulty, SERVER.toString(), "--continue", "--alarms", alarms.toString());
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("3 violations, " + events(trace) + " events checked, 0 lines rejected"), r.out());
        assertEquals(List.of(1L, 2L, 3L), Files.readAllLines(alarms).stream()
                .map(l -> (Long) ((Map<?, ?>) Json.parse(l)).get("number")).toList());
        CommandRun stop = monitor(dir, "c.jsonl", faulty, SERVER.toString());
        assertTrue(stop.out().contains("1 violation, ") && stop.out().contains("(stopped at the first violation)"),
                stop.out());
    }

    @Test
    void badLinesAreReportedWithTheirPlaceCountedAndRaiseNoAlarm(@TempDir Path dir) throws Exception {
        List<String> trace = record(dir, SERVER, 6, 500);
        List<String> json = new ArrayList<>(trace);
        json.add(3, "{\"kind\":\"output\",\"t_us\":");
        json.add(5, "{\"kind\":\"output\",\"t_us\":1,\"channel\":\"nothing\",\"values\":{}}");
        json.add(7, "{\"kind\":\"input\",\"channel\":\"req\",\"values\":{\"n\":1}}");
        CommandRun r = monitor(dir, "bad.jsonl", json, SERVER.toString());
        assertEquals(3, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("no violation, " + events(trace) + " events checked, 3 lines rejected"), r.out());
        List<String> err = r.err().lines().toList();
        assertEquals(3, err.size(), r.err());
        assertTrue(err.get(0).startsWith(dir.resolve("bad.jsonl") + ":4: "), err.get(0));
        assertTrue(err.get(1).startsWith(dir.resolve("bad.jsonl") + ":6: 'nothing' is not an observable channel"),
                err.get(1));
        assertTrue(err.get(2).startsWith(dir.resolve("bad.jsonl") + ":8: no \"t_us\""), err.get(2));
        List<String> csv = new ArrayList<>(csv(trace));
        csv.add(2, "soon,req,n=1");
        csv.add(4, "5,resp,n");
        csv.add(6, "6,resp,n=1,extra");
        CommandRun c = monitor(dir, "bad.csv", csv, SERVER.toString());
        assertEquals(3, c.exit(), c.out() + c.err());
        assertTrue(c.out().contains("3 lines rejected"), c.out());
        assertEquals(List.of(dir.resolve("bad.csv") + ":3: time 'soon' is no whole number of microseconds",
                dir.resolve("bad.csv") + ":5: value 'n' is not name=value",
                dir.resolve("bad.csv") + ":7: expected t_us,channel,values: 4 fields"), c.err().lines().toList());
    }

    @Test
    void quotedCsvFieldsAreReadAsRfc4180QuotesThemAndBadQuotingIsARejectedLine(@TempDir Path dir) throws Exception {
        // a spreadsheet's export: every field quoted, the header too, a space after a comma
        List<String> quoted = List.of("\"t_us\",\"channel\",\"values\"", "\"1000\",\"req\",\"n=4\"",
                "2500, \"resp\", \"n=5\"", "6000,req,\"n=8\"", "7500,\"resp\",n=9");
        expect(0, "no violation, 4 events checked, 0 lines rejected", dir, "q.csv", quoted, SERVER.toString(), "--end",
                "9000");
        // a comma inside quotes is part of the field: here a value that is no integer, said as such
        List<String> bad = List.of("t_us,channel,values", "1000,req,\"n=4,5\"", "2500,\"resp,n=5",
                "3000,\"resp\"x,n=5", "3500,re\"q,n=1");
        CommandRun b = monitor(dir, "b.csv", bad, SERVER.toString());
        assertEquals(3, b.exit(), b.out() + b.err());
        assertEquals(List.of(dir.resolve("b.csv") + ":2: value of 'n' is not a 32-bit integer: 4,5",
                dir.resolve("b.csv") + ":3: the quote at column 6 is not closed",
                dir.resolve("b.csv") + ":4: column 12: a quoted field is followed by 'x', not by a comma",
                dir.resolve("b.csv") + ":5: column 8: a quote inside a field that does not start with one"),
                b.err().lines().toList());
    }

    @Test
    void aToleranceTakesEachEventsTimeGiveOrTake(@TempDir Path dir) throws Exception {
        List<String> log = List.of("t_us,channel,values", "1000,req,n=1", "1800,resp,n=2");
        assertEquals(2, monitor(dir, "l.csv", log, SERVER.toString()).exit());
        CommandRun r = monitor(dir, "l.csv", log, SERVER.toString(), "--tolerance", "300");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("event times give or take 300 us"), r.out());
        // the largest tolerance: each event's window reaches as far as DTRON can time, and nothing overflows
        expect(0, "no violation, 2 events checked, 0 lines rejected", dir, "l.csv", log, SERVER.toString(),
                "--tolerance", "9223372036854775");
        CommandRun negative = monitor(dir, "l.csv", log, SERVER.toString(), "--tolerance", "-1");
        assertEquals(1, negative.exit());
        assertTrue(negative.err().startsWith("dtron monitor: --tolerance must be 0 to 9223372036854775 us"),
                negative.err());
    }

    @Test
    void badBytesAndHugeNumbersAreRejectedLinesAndTheReplayGoesOn(@TempDir Path dir) throws Exception {
        List<String> trace = record(dir, SERVER, 7, 100);
        java.io.ByteArrayOutputStream bytes = new java.io.ByteArrayOutputStream();
        bytes.write(new byte[] {(byte) 0xEF, (byte) 0xBB, (byte) 0xBF}); // a byte order mark before the start line
        for (String line : trace) {
            bytes.write((line + "\n").getBytes(StandardCharsets.UTF_8));
            if (line.contains("\"kind\":\"start\"")) {
                bytes.write("{\"t_us\":1,\"channel\":\"r\u00e9q\"}\n".getBytes(StandardCharsets.ISO_8859_1));
                bytes.write(("{\"t_us\":" + "9".repeat(100_000) + "}\n").getBytes(StandardCharsets.UTF_8));
                bytes.write("{\"t_us\":9223372036854775000,\"channel\":\"req\"}\n".getBytes(StandardCharsets.UTF_8));
            }
        }
        Path file = dir.resolve("bad.jsonl");
        Files.write(file, bytes.toByteArray());
        CommandRun r = CommandRun.of("monitor", SERVER.toString(), "--replay", file.toString());
        assertEquals(3, r.exit(), "the correct run's events pass, three lines are rejected: " + r.out() + r.err());
        assertTrue(r.out().contains("time units of 1000 us"), "the start line after the mark is read: " + r.out());
        assertTrue(r.err().contains("bad.jsonl:2: not UTF-8 text (a byte at column 23 is no UTF-8 character)"),
                r.err());
        assertTrue(r.err().contains("bad.jsonl:3: column 9: a number of 100000 characters is longer than"
                + " DTRON reads (at most 100)"), r.err());
        assertTrue(r.err().contains("bad.jsonl:4: time 9223372036854775000 us is later than DTRON can time"), r.err());
        assertTrue(r.err().length() < 2_000, "a long line is not echoed: " + r.err().length());
        assertTrue(r.out().contains("no violation, "), r.out());
        assertTrue(r.out().contains(", 3 lines rejected"), r.out());
    }

    @Test
    void outputsThatWouldDestroyAnInputOrCannotBeWrittenAreRefusedBeforeTheReplay(@TempDir Path dir) throws Exception {
        List<String> lines = csv(record(dir, SERVER, 7, 100));
        Path log = dir.resolve("l.csv");
        Files.write(log, lines, StandardCharsets.UTF_8);
        for (String[] output : new String[][] {{"--alarms", log.toString()}, {"--junit", log.toString()},
                {"--junit", SERVER.toString()}}) {
            CommandRun r = CommandRun.of("monitor", SERVER.toString(), "--replay", log.toString(), output[0],
                    output[1]);
            assertEquals(1, r.exit(), r.out() + r.err());
            assertTrue(r.err().startsWith("dtron monitor: " + output[0] + " " + output[1] + ": is the command's"
                    + " input "), r.err());
            assertEquals("", r.out(), "refused before the replay");
        }
        assertEquals(lines, Files.readAllLines(log, StandardCharsets.UTF_8), "the trace is untouched");
        CommandRun folder = CommandRun.of("monitor", SERVER.toString(), "--replay", log.toString(), "--junit",
                dir.toString());
        assertEquals(1, folder.exit());
        assertTrue(folder.err().startsWith("dtron monitor: --junit " + dir + ": is a folder; give a file in it"),
                folder.err());
        Path badUnit = dir.resolve("unit.jsonl");
        Files.writeString(badUnit, "{\"kind\":\"start\",\"timeunit_us\":-7}\n");
        CommandRun unit = CommandRun.of("monitor", SERVER.toString(), "--replay", badUnit.toString());
        assertEquals(1, unit.exit());
        assertEquals("dtron monitor: " + badUnit + ":1: the start line's timeunit_us -7 is no positive number of"
                + " microseconds (at most 9223372036854775): give the time unit with --timeunit", unit.err().strip());
    }

    @Test
    void aWrongStartOrFileIsAOneLineError(@TempDir Path dir) throws Exception {
        List<String> trace = record(dir, SERVER, 7, 100);
        CommandRun r = monitor(dir, "t.jsonl", trace, SERVER.toString(), "--from", "Server.Nowhere");
        assertEquals(1, r.exit());
        assertTrue(r.err().startsWith("dtron monitor: --from: "), r.err());
        CommandRun missing = CommandRun.of("monitor", SERVER.toString(), "--replay", dir.resolve("none.jsonl").toString());
        assertEquals(1, missing.exit());
        assertEquals("dtron monitor: cannot read " + dir.resolve("none.jsonl") + ": no such file",
                missing.err().strip());
        CommandRun runs = CommandRun.of("monitor", SERVER.toString(), "--cluster", "never-joined", "--runs", "-1");
        assertEquals(1, runs.exit());
        assertTrue(runs.err().startsWith("dtron monitor: --runs must be a number of runs, at least 0 (0: every run):"
                + " -1"), runs.err());
        CommandRun replayRuns = CommandRun.of("monitor", SERVER.toString(), "--replay", dir.resolve("none.jsonl")
                .toString(), "--runs", "2");
        assertEquals(1, replayRuns.exit());
        assertTrue(replayRuns.err().contains("--runs and --shield are for watching a bus"), replayRuns.err());
        CommandRun both = CommandRun.of("monitor", SERVER.toString(), "--cluster", "never-joined", "--key-file",
                dir.resolve("bus.key").toString(), "--insecure");
        assertEquals(1, both.exit());
        assertTrue(both.err().startsWith("dtron monitor: --insecure uses no secret: leave out --key-file"), both.err());
        CommandRun replayInsecure = CommandRun.of("monitor", SERVER.toString(), "--replay", dir.resolve("none.jsonl")
                .toString(), "--insecure");
        assertEquals(1, replayInsecure.exit());
        assertTrue(replayInsecure.err().startsWith("dtron monitor: --bind, --key-file, --insecure, --delta,"),
                replayInsecure.err());
    }
}
