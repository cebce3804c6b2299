package io.dtron.cli;

import io.dtron.api.internal.TesterSide;
import static org.awaitility.Awaitility.await;
import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.IDtronChannel;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import io.dtron.model.ModelLoader;
import io.dtron.model.TestInterface;
import io.dtron.testadapter.BusTicker;
import io.dtron.testsupport.BusSummary;
import io.dtron.testsupport.TickerRunBounds;
import io.dtron.testsupport.Waits;
import java.io.File;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class RunCommandTest {
    static final String TICKER = """
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

    @Test
    void aStatisticalModelIsRefusedWithOneMessageNamingTheFeatureThePlaceAndWhy() throws IOException {
        Path smc = dir.resolve("ticker-smc.xta");
        Files.writeString(smc, TICKER.replace("system Ticker, Env;", "int jitter;\nsystem Ticker, Env;")
                .replace("assign e = 0;", "assign e = 0, jitter = fint(random(3));"));
        CommandRun check = CommandRun.of("check", smc.toString());
        assertEquals(0, check.exit(), check.err());
        CommandRun r = CommandRun.of("run", smc.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertEquals("dtron run: " + smc + ": the model cannot start: " + smc + ":8:92: error: the built-in function"
                + " 'random' cannot be run by DTRON's engine: the engine evaluates the integer functions of the model,"
                + " not the real-valued and random functions of statistical model checking (template Env, assignment"
                + " label)", r.err().strip());
    }

    @Test
    void aHybridClockModelIsCheckedAndRefusedByRunWithTheConstructItsPlaceAndWhy() throws IOException {
        // Uppaal 5 sets a clock to another clock in statistical model checking; DTRON's zones cannot
        Path hybrid = dir.resolve("ticker-hybrid.xta");
        Files.writeString(hybrid, TICKER.replace("process Env() { clock e;", "process Env() { clock e, f;")
                .replace("assign e = 0;", "assign e = 0, f = e;"));
        CommandRun check = CommandRun.of("check", hybrid.toString());
        assertEquals(0, check.exit(), check.err());
        assertTrue(check.out().contains(hybrid + ":8:78: warning: a clock set to a real number or to another clock"
                + " cannot be run by DTRON's engine"), check.out());
        CommandRun r = CommandRun.of("run", hybrid.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertEquals("dtron run: " + hybrid + ": the model cannot start: " + hybrid + ":8:78: error: a clock set to a"
                + " real number or to another clock cannot be run by DTRON's engine: the engine resets clocks to"
                + " integers, as zones need (template Env, assignment label)", r.err().strip());
    }

    @Test
    void aCorrectSystemPassesWithExitCodeZero() {
        CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time", "--seed", "7",
                "--timeout", "300");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("seed 7"), r.out());
        assertTrue(r.out().contains("PASSED: the timeout of 300 time units was reached"), r.out());
        assertTrue(r.out().matches("(?s).*statistics: 7 PASSED \\d+ \\d+ 300000 .*"), r.out());
    }

    @Test
    void aFaultySystemFailsWithExitCodeTwoAndAnExplanation() {
        CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName() + ":slow", "--virtual-time",
                "--seed", "7", "--timeout", "300");
        assertEquals(2, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("FAILED: no output came by t=12.000"), r.out());
        assertTrue(r.out().contains("tick between t=8.000 and t=12.000 (Ticker: Running -> Running)"), r.out());
    }

    @Test
    void aQuietRunInRealTimeShowsProgressWithTheNextDeadline() {
        // 0.6 s per unit: the slow ticker's first tick is due by t=12 (7.2 s) and comes at t=13; nothing happens
        // before, and a progress line comes after 5 s
        CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName() + ":slow", "--seed", "1",
                "--timeunit", "600000", "--timeout", "100");
        assertEquals(2, r.exit(), r.out() + r.err());
        Matcher progress = Pattern.compile("progress: \\d+ s elapsed, t=(\\d+)\\.\\d{3}, 0 inputs, 0 outputs, an output"
                + " is due by t=12\\.000\n").matcher(r.out().replace(System.lineSeparator(), "\n"));
        assertTrue(progress.find(), r.out());
        assertTrue(Integer.parseInt(progress.group(1)) <= 12, "the test time while waiting: " + r.out());
        assertTrue(progress.start() < r.out().indexOf("FAILED: no output came by t=12.000"), r.out());
        // in real time the tester measures how late its thread wakes up before the run, and aims inputs inside that
        Matcher margin = Pattern.compile("dtron run: the tester's thread wakes up to [0-9.]+ ms late here; inputs are"
                + " aimed at least ([0-9.]+) ms \\(([0-9.]+) time units\\) inside the end of their windows")
                .matcher(r.out());
        assertTrue(margin.find(), r.out());
        assertTrue(Double.parseDouble(margin.group(1)) >= 2.0, "at least the default 2 ms: " + r.out());
        assertEquals(Double.parseDouble(margin.group(1)) / 600, Double.parseDouble(margin.group(2)), 0.001, r.out());
    }

    @Test
    void theSameSeedGivesTheSameTraceByteForByte() throws IOException {
        Path a = dir.resolve("a.jsonl");
        Path b = dir.resolve("b.jsonl");
        for (Path trace : List.of(a, b)) {
            CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time", "--seed",
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
        CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time", "--seed", "43",
                "--timeout", "500", "--trace", c.toString());
        assertFalse(java.util.Arrays.equals(Files.readAllBytes(a), Files.readAllBytes(c)), "another seed, another run");
    }

    @Test
    void anInputAppliedLaterThanItWasSentStandsInTheTraceWhereTheTesterPlacedItAndReplaysAsJudged() throws IOException {
        // the sticky ticker applies each reset 3 units after it is performed and reports so: its next tick comes 13
        // units after the reset was sent, which the model allows only from where the reset was applied
        Path trace = dir.resolve("sticky.jsonl");
        CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName() + ":sticky",
                "--virtual-time", "--seed", "3", "--timeout", "300", "--trace", trace.toString());
        assertEquals(0, r.exit(), r.out() + r.err());
        List<String> lines = Files.readAllLines(trace);
        List<String> inputs = lines.stream().filter(l -> l.startsWith("{\"kind\":\"input\"")).toList();
        assertFalse(inputs.isEmpty(), "resets were sent");
        java.util.regex.Pattern placed = java.util.regex.Pattern.compile("\"t_us\":(\\d+),.*\"sent_us\":(\\d+)");
        for (String input : inputs) {
            java.util.regex.Matcher m = placed.matcher(input);
            assertTrue(m.find(), "an input placed where it was applied: " + input);
            assertEquals(3000, Long.parseLong(m.group(1)) - Long.parseLong(m.group(2)), input);
        }
        long last = -1;
        int events = 0;
        for (String line : lines.subList(1, lines.size() - 1)) {
            java.util.regex.Matcher m = java.util.regex.Pattern.compile("\"t_us\":(\\d+)").matcher(line);
            if (line.startsWith("{\"kind\":\"input\"") || line.startsWith("{\"kind\":\"output\"")) {
                assertTrue(m.find());
                long t = Long.parseLong(m.group(1));
                assertTrue(t >= last, "events in the order of their times: " + line);
                last = t;
                events++;
            }
        }
        CommandRun replay = CommandRun.of("monitor", model.toString(), "--replay", trace.toString());
        assertEquals(0, replay.exit(), replay.out() + replay.err());
        assertTrue(replay.out().contains("no violation, " + events + " events checked"), replay.out());
    }

    @Test
    void usageErrorsExitWithOneAndSayWhy() {
        CommandRun noClass = CommandRun.of("run", model.toString(), "--sut", "no.such.Sut", "--virtual-time");
        assertEquals(1, noClass.exit());
        assertTrue(noClass.err().contains("no class no.such.Sut on the classpath"), noClass.err());
        CommandRun notAdapter = CommandRun.of("run", model.toString(), "--sut", "java.lang.String", "--virtual-time");
        assertEquals(1, notAdapter.exit());
        assertTrue(notAdapter.err().contains("does not implement io.dtron.engine.Adapter"), notAdapter.err());
        CommandRun variant = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName() + ":weird");
        assertEquals(1, variant.exit());
        assertTrue(variant.err().contains("unknown variant 'weird' (correct, slow, broken, jammed, burning, sticky)"), variant.err());
        CommandRun policy = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--delay-policy", "soon");
        assertEquals(1, policy.exit());
        assertTrue(policy.err().contains("unknown delay policy 'soon'"), policy.err());
        CommandRun badTimeout = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--timeout", "0");
        assertEquals(1, badTimeout.exit());
        assertTrue(badTimeout.err().contains("the timeout must be a positive number"), badTimeout.err());
        assertFalse((noClass.err() + variant.err() + policy.err()).contains("\tat "), "no stack traces");
        for (CommandRun r : List.of(noClass, notAdapter, variant, policy, badTimeout)) {
            assertOneLineUsageError(r);
        }
    }

    @Test
    void theClasspathTakesThePlatformsPathSeparatorAndCommas() throws IOException {
        Path a = Files.createDirectories(dir.resolve("cp-a"));
        Path b = Files.createDirectories(dir.resolve("cp-b"));
        Path c = Files.createDirectories(dir.resolve("cp-c"));
        CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time", "--seed", "7",
                "--timeout", "50", "--classpath", a + File.pathSeparator + b + "," + c);
        assertEquals(0, r.exit(), r.out() + r.err());
        Path missing = dir.resolve("cp-missing");
        CommandRun bad = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time",
                "--classpath", a + File.pathSeparator + missing);
        assertOneLineUsageError(bad);
        assertTrue(bad.err().contains("--classpath entry " + missing + " does not exist"), "one entry: " + bad.err());
    }

    @Test
    void theHelpNamesEveryModelFormatAndThePathSeparator() {
        CommandRun help = CommandRun.of("run", "--help");
        assertEquals(0, help.exit(), help.err());
        String text = help.out().replaceAll("\\s+", " ");
        assertTrue(text.contains("The model (.xml, .xta, or an Uppaal 3 .ta)."), help.out());
        assertTrue(text.contains("separated by '" + File.pathSeparator + "' or commas"), help.out());
    }

    @Test
    void aRunLongerThanDtronCanTimeIsAUsageErrorNamingTheLimit() {
        CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time",
                "--timeunit", Long.toString(Long.MAX_VALUE), "--timeout", Integer.toString(Integer.MAX_VALUE));
        assertOneLineUsageError(r);
        assertTrue(r.err().startsWith("dtron run: the timeout of 2147483647 time units of 9223372036854775807 us is"
                + " longer than DTRON can time: at most 9223372036854775 us (about 292 years)"), r.err());
        assertFalse(r.err().contains("Exception"), r.err());
        CommandRun bound = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time",
                "--delay-policy", "random-bounded", "--delay-bound", Long.toString(Long.MAX_VALUE));
        assertOneLineUsageError(bound);
        assertTrue(bound.err().contains("the delay bound of 9223372036854775807 time units of 1000 us is longer"),
                bound.err());
        CommandRun longest = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName() + ":slow",
                "--virtual-time", "--seed", "7", "--timeunit", "1000", "--timeout",
                Long.toString(9_223_372_036_854_775L / 1000));
        assertEquals(2, longest.exit(), "the longest run is timed without overflow: " + longest.out() + longest.err());
        assertTrue(longest.out().contains("FAILED: no output came by t=12.000"), longest.out());
    }

    @Test
    void aDelayBoundGoesWithTheBoundedPolicyAndItNeedsOne() {
        CommandRun none = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--delay-policy", "random-bounded");
        assertOneLineUsageError(none);
        assertTrue(none.err().startsWith("dtron run: --delay-policy random-bounded needs --delay-bound N or"
                + " SHORT,LONG"), none.err());
        CommandRun eager = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--delay-policy", "eager", "--delay-bound", "5");
        assertOneLineUsageError(eager);
        assertTrue(eager.err().startsWith("dtron run: --delay-bound 5 bounds the delays of --delay-policy"
                + " random-bounded only, not of eager"), eager.err());
        CommandRun bounded = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(),
                "--virtual-time", "--seed", "1", "--timeout", "50", "--delay-policy", "random-bounded",
                "--delay-bound", "1,5");
        assertEquals(0, bounded.exit(), bounded.out() + bounded.err());
    }

    @Test
    void aSystemUnderTestThatThrowsEndsTheRunInconclusiveOnOneLineAndItsReportsAreWritten() throws IOException {
        // thrown when it starts, when an input is applied, and in a task it scheduled (its second tick, at 20)
        String[][] cases = {
            {"broken", "the system under test threw IllegalStateException: the ticker is unplugged, at"
                    + " io.dtron.cli.TickerForTests.start(TickerForTests.java:", " when it was started"},
            {"jammed", "the system under test threw IllegalStateException: the reset button is jammed, at"
                    + " io.dtron.cli.TickerForTests.perform(TickerForTests.java:", " when input reset() was applied at"
                    + " t="},
            {"burning", "a task of the system under test threw IllegalStateException: the ticker burnt out, at"
                    + " io.dtron.cli.TickerForTests.lambda$arm$", " (at t=20.000)"},
        };
        for (String[] c : cases) {
            Path junit = dir.resolve("thrown-" + c[0] + ".xml");
            Path trace = dir.resolve("thrown-" + c[0] + ".jsonl");
            Path coverage = dir.resolve("thrown-" + c[0] + ".json");
            CommandRun r = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName() + ":" + c[0],
                    "--virtual-time", "--seed", "1", "--timeout", "100", "--junit", junit.toString(), "--trace",
                    trace.toString(), "--coverage", coverage.toString());
            assertEquals(3, r.exit(), r.out() + r.err());
            assertEquals("", r.err(), "no stack trace, no error line: the verdict says it");
            String verdict = r.out().lines().filter(l -> l.startsWith("INCONCLUSIVE: ")).findFirst().orElseThrow();
            assertTrue(verdict.startsWith("INCONCLUSIVE: " + c[1]), verdict);
            assertTrue(verdict.contains(c[2]), verdict);
            assertFalse(r.out().contains("\tat "), r.out());
            String xml = Files.readString(junit);
            assertTrue(xml.contains("type=\"INCONCLUSIVE\"") && xml.contains("threw IllegalStateException: "), xml);
            assertTrue(Files.readString(trace).contains("\"verdict\":\"INCONCLUSIVE\""), Files.readString(trace));
            assertTrue(Files.readString(coverage).contains("\"dtron_coverage\": 1"), Files.readString(coverage));
        }
    }

    @Test
    void aModelFileAloneMeansRun() {
        CommandRun r = CommandRun.of(model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-time", "--seed", "7",
                "--timeout", "300");
        assertEquals(0, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("PASSED: the timeout of 300 time units was reached"), r.out());
        CommandRun typo = CommandRun.of("chek", model.toString());
        assertEquals(1, typo.exit());
        assertTrue(typo.err().contains("Unmatched argument"), "a command name is not taken for a model: " + typo.err());
    }

    /** A usage error is its reason and where the help is, not the whole usage message; exit code 1. */
    private static void assertOneLineUsageError(CommandRun r) {
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.err().startsWith("dtron run: "), r.err());
        assertTrue(r.err().endsWith("see 'dtron run --help'" + System.lineSeparator()), r.err());
        assertFalse(r.err().contains("Usage:") || r.err().contains("--wait-for-adapters=channels|N"), r.err());
        assertTrue(r.err().lines().count() <= 3, "the reason, maybe a suggestion, and the help: " + r.err());
    }

    @Test
    void theNatsOptionsAreCheckedBeforeAnythingConnects() throws IOException {
        Path password = Files.writeString(dir.resolve("password"), "secret\n");
        CommandRun badUrl = CommandRun.of(model.toString(), "--bus", "http://127.0.0.1:4222");
        assertOneLineUsageError(badUrl);
        assertTrue(badUrl.err().contains("--bus takes NATS server URLs"), badUrl.err());
        CommandRun withBind = CommandRun.of(model.toString(), "--bus", "nats://127.0.0.1:4222", "--bind", "127.0.0.1");
        assertOneLineUsageError(withBind);
        assertTrue(withBind.err().contains("--bind is the interface of the embedded JGroups bus"), withBind.err());
        CommandRun withoutBus = CommandRun.of(model.toString(), "--nats-user", "u", "--nats-password-file",
                password.toString());
        assertOneLineUsageError(withoutBus);
        assertTrue(withoutBus.err().contains("are for a NATS bus"), withoutBus.err());
        CommandRun userAlone = CommandRun.of(model.toString(), "--bus", "nats://127.0.0.1:4222", "--nats-user", "u");
        assertOneLineUsageError(userAlone);
        assertTrue(userAlone.err().contains("--nats-user and --nats-password-file go together"), userAlone.err());
        CommandRun badName = CommandRun.of(model.toString(), "--bus", "nats://127.0.0.1:4222", "--cluster", "a.b");
        assertOneLineUsageError(badName);
        assertTrue(badName.err().contains("a NATS bus name is 1 to 64 letters"), badName.err());
        CommandRun withSut = CommandRun.of(model.toString(), "--sut", TickerForTests.class.getName(), "--bus",
                "nats://127.0.0.1:4222");
        assertOneLineUsageError(withSut);
        assertTrue(withSut.err().contains("--bus is the bus of the adapters"), withSut.err());
    }

    @Test
    void unknownOptionsAndBadValuesGetTheReasonAndWhereTheHelpIs() {
        CommandRun unknown = CommandRun.of(model.toString(), "--bogus");
        assertOneLineUsageError(unknown);
        assertTrue(unknown.err().startsWith("dtron run: Unknown option: '--bogus'"), unknown.err());
        CommandRun notANumber = CommandRun.of(model.toString(), "--wait-timeout", "two");
        assertOneLineUsageError(notANumber);
        assertTrue(notANumber.err().contains("Invalid value for option '--wait-timeout': 'two'"),
                notANumber.err());
        CommandRun missing = CommandRun.of("run");
        assertOneLineUsageError(missing);
        assertTrue(missing.err().contains("Missing required parameter: 'MODEL'"), missing.err());
        CommandRun typo = CommandRun.of("run", model.toString(), "--sut", TickerForTests.class.getName(), "--virtual-tim");
        assertOneLineUsageError(typo);
        assertTrue(typo.err().contains("--virtual-time"), "a suggestion: " + typo.err());
        for (String[] args : List.of(
                new String[] {"--wait-for-adapters", "-1"},
                new String[] {"--wait-timeout", "0"},
                new String[] {"--wait-timeout", Long.toString(Long.MAX_VALUE)},
                new String[] {"--virtual-time"},
                new String[] {"--bind", "no.such.host.invalid"},
                new String[] {"--cluster", " "},
                new String[] {"--adapter", "java.lang.String"},
                new String[] {"--sut", TickerForTests.class.getName(), "--cluster", "x"})) {
            List<String> all = new ArrayList<>(List.of(model.toString()));
            all.addAll(List.of(args));
            assertOneLineUsageError(CommandRun.of(all.toArray(new String[0])));
        }
        CommandRun virtual = CommandRun.of(model.toString(), "--virtual-time");
        assertTrue(virtual.err().contains("--virtual-time needs --sut or --tron-adapter: the adapters on a bus live in real time"),
                virtual.err());
        CommandRun notBusAdapter = CommandRun.of(model.toString(), "--adapter", "java.lang.String");
        assertTrue(notBusAdapter.err().contains("java.lang.String is not a bus adapter: it does not implement"
                + " io.dtron.api.DtronAdapter"), notBusAdapter.err());
        CommandRun mixed = CommandRun.of(model.toString(), "--sut", TickerForTests.class.getName(), "--cluster", "x");
        assertTrue(mixed.err().contains("are for testing the adapters on a bus, without --sut"), mixed.err());
        CommandRun bindWithSut = CommandRun.of(model.toString(), "--sut", TickerForTests.class.getName(), "--bind", "127.0.0.1");
        assertEquals(1, bindWithSut.exit());
        assertTrue(bindWithSut.err().contains("with --sut leave it out"), bindWithSut.err());
    }

    @Test
    void aBusAdapterInThisJvmPassesAndPrintsTheLatency() {
        // 25 ms per unit: the model's 2 units of jitter, 50 ms; a machine that holds the ticker's timer up longer
        // makes the system late (FAILED, and the ticker says so), or the tester's own input (INCONCLUSIVE, it says so)
        int heldUp = BusTicker.heldUpTicks();
        CommandRun r = CommandRun.of(model.toString(), "--adapter", BusTicker.class.getName(), "--cluster", cluster(), "--timeunit",
                "25000", "--timeout", "100", "--delay-policy", "eager", "--seed", "3");
        assertTrue(r.out().contains("adapter " + BusTicker.class.getName() + " joined as "), r.out() + r.err());
        TickerRunBounds.assertPassedUnlessHeldUp(r.exit(), r.out() + r.err(), 100, heldUp);
        assertTrue(r.out().contains("latency t2 - t1 of inputs back from the bus: count "), r.out());
        BusSummary.assertNothingOfTheRunRejected(r.out());
        assertTrue(r.out().contains(", listener failures 0"), r.out());
    }

    @Test
    void aFaultyBusAdapterFails() {
        CommandRun r = CommandRun.of(model.toString(), "--adapter", BusTicker.class.getName() + ":slow", "--cluster", cluster(),
                "--timeunit", "10000", "--timeout", "100", "--seed", "3");
        assertEquals(2, r.exit(), r.out() + r.err());
        // the tick due by 12 comes at 13 by the adapter's clock, within the reorder window: judged at its time
        TickerRunBounds.assertSlowTickerFailed(r.out());
        assertTrue(r.out().contains("latency t2 - t1 of outputs: count "), r.out());
    }

    @Test
    void aSecondTesterOnABusWithARunRefusesToStartAndNamesTheOtherTester() throws Exception {
        TestInterface testInterface = TestInterface.fromNames(ModelLoader.load(model));
        String shared = cluster();
        try (BusSession first = BusSession.open(testInterface,
                () -> DtronOptions.builder().clusterName(shared).bindAddress(InetAddress.getLoopbackAddress()), false)) {
            String tester = first.run().memberId();
            CommandRun second = CommandRun.of(model.toString(), "--adapter", BusTicker.class.getName(), "--cluster", shared,
                    "--timeunit", "10000", "--timeout", "100");
            assertEquals(1, second.exit(), second.out() + second.err());
            assertTrue(second.err().contains("dtron run: bus '" + shared + "' at 127.0.0.1 has a run in progress:"
                    + " tester " + tester + " is on it"), second.err());
            assertTrue(second.err().contains("--cluster NAME"), second.err());
            assertFalse(second.out().contains("PASSED") || second.out().contains("FAILED"), second.out());
        }
    }

    @Test
    void ofTwoTestersOnOneBusTheFirstRunsAndTheSecondIsRefusedLeavingNoTrace() throws Exception {
        String shared = cluster();
        String[] args = {model.toString(), "--adapter", BusTicker.class.getName(), "--cluster", shared, "--timeunit",
                "10000", "--timeout", "200"};
        // a member that stays on the bus through both, to see when the first tester is there
        try (Dtron watcher = Dtron.connect(DtronOptions.builder().clusterName(shared).memberName("watcher").build())) {
            CompletableFuture<CommandRun> first = CompletableFuture.supplyAsync(() -> CommandRun.of(args));
            await().atMost(Duration.ofSeconds(60)).until(() -> !TesterSide.of(watcher).getOtherTesters().isEmpty());
            CommandRun second = CommandRun.of(args);
            assertEquals(1, second.exit(), second.out() + second.err());
            assertTrue(second.err().contains("has a run in progress"), second.err());
            // it decided before its adapter joined: nothing of it served, or could disturb, the first run
            assertFalse(second.out().contains("joined as"), second.out());
            CommandRun run = first.get(2, TimeUnit.MINUTES);
            // the verdict is the first run's own: the second tester's leaving is no reason to end it (a ticker held
            // up by the machine's load may still fail it, which its own warning says, so only INCONCLUSIVE is wrong)
            assertFalse(run.out().contains("left the bus"), run.out());
            assertTrue(run.exit() == 0 || run.exit() == 2, run.out() + run.err());
        }
    }

    @Test
    void withoutAdaptersARunWaitsUntilEveryChannelIsServedAndSaysWhichAreMissing() {
        CommandRun alone = CommandRun.of(model.toString(), "--cluster", cluster(), "--wait-timeout", "1");
        assertEquals(1, alone.exit(), alone.out() + alone.err());
        assertTrue(alone.out().contains("serves every channel of the model; missing: input reset, output tick"),
                alone.out());
        assertTrue(alone.err().contains("served input reset, output tick; no adapter on the bus said which channels"
                + " it serves"), alone.err());
        assertTrue(alone.err().contains("--wait-for-adapters N"), alone.err());
        assertFalse(alone.out().contains("PASSED") || alone.out().contains("FAILED"), "no run: " + alone.out());
    }

    @Test
    void anAdapterServingPartOfTheModelIsNamedWithWhatItServes() {
        String bus = cluster();
        try (Dtron half = Dtron.connect(DtronOptions.builder().clusterName(bus).memberName("half-adapter").build())) {
            half.addDtronListener(new DtronListener(IDtronChannel.of("reset")) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                }
            });
            CommandRun r = CommandRun.of(model.toString(), "--cluster", bus, "--wait-timeout", "2");
            assertEquals(1, r.exit(), r.out() + r.err());
            assertTrue(r.err().contains("served output tick; half-adapter receives [reset] and sends []"), r.err());
        }
    }

    @Test
    void aBadWaitForAdaptersValueIsAUsageError() {
        CommandRun r = CommandRun.of(model.toString(), "--wait-for-adapters", "two");
        assertOneLineUsageError(r);
        assertTrue(r.err().contains("--wait-for-adapters takes 'channels' or a number of adapters (0 or more): two"),
                r.err());
    }

    @Test
    void outputsAfterTheEndAreCountedInTheSummary() throws Exception {
        TestInterface testInterface = TestInterface.fromNames(ModelLoader.load(model));
        List<Dtron> member = new ArrayList<>();
        String cluster = cluster();
        try (BusSession session = BusSession.open(testInterface,
                () -> DtronOptions.builder().clusterName(cluster).bindAddress(InetAddress.getLoopbackAddress()), false)) {
            session.startAdapter(member::add);
            assertTrue(session.awaitAdapters(1, Duration.ofSeconds(30)), session.run().members().toString());
            session.bridge().start(new AdapterContext() {
                @Override
                public void report(Event output) {
                }

                @Override
                public void report(Event output, long eventMicros) {
                }

                @Override
                public void inputApplied(long ordinal, long eventMicros) {
                }

                @Override
                public void inconclusive(String reason) {
                }

                @Override
                public TestClock clock() {
                    return new TestClock() {
                        @Override
                        public long nowMicros() {
                            return 0;
                        }

                        @Override
                        public Scheduled schedule(long delayMicros, Runnable task) {
                            throw new UnsupportedOperationException("the bridge schedules nothing");
                        }
                    };
                }

                @Override
                public TestInterface testInterface() {
                    return testInterface;
                }

                @Override
                public long timeUnitMicros() {
                    return 1000;
                }
            });
            session.bridge().stop();
            IDtronChannel tick = IDtronChannel.of("tick", "seq");
            member.get(0).send(tick.constructValued(Map.of("seq", 1)));
            member.get(0).send(tick.constructValued(Map.of("seq", 2)));
            Waits.await("2 outputs after the end").until(() -> session.run().outputsAfterEnd() >= 2);
            StringWriter summary = new StringWriter();
            session.printSummary(new PrintWriter(summary, true));
            assertTrue(summary.toString().contains(", 2 outputs after the end (not judged)"), summary.toString());
        }
    }

    @Test
    void waitingForAdaptersThatDoNotComeEndsWithAClearMessage() {
        CommandRun r = CommandRun.of(model.toString(), "--cluster", cluster(), "--wait-for-adapters", "1", "--wait-timeout", "1");
        assertEquals(1, r.exit(), r.out() + r.err());
        assertTrue(r.out().contains("waiting up to 1 s for 1 adapter to join bus '"), r.out());
        assertTrue(r.err().contains("only 0 of 1 adapters joined bus '"), r.err());
        assertFalse(r.out().contains("PASSED") || r.out().contains("FAILED"), "no run: " + r.out());
    }

    private static String cluster() {
        return "run-" + UUID.randomUUID().toString().substring(0, 8);
    }
}
