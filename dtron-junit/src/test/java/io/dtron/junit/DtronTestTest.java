package io.dtron.junit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.platform.engine.discovery.DiscoverySelectors.selectClass;
import static org.junit.platform.engine.discovery.DiscoverySelectors.selectMethod;

import io.dtron.junit.internal.DtronExtension;
import io.dtron.junit.internal.Inconclusive;
import io.dtron.testsupport.NatsServer;
import java.io.File;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Properties;
import java.util.concurrent.TimeUnit;
import java.util.regex.Pattern;
import java.util.stream.Collectors;
import java.util.stream.Stream;
import java.io.ByteArrayOutputStream;
import java.io.PrintStream;
import java.io.Reader;
import java.nio.charset.StandardCharsets;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.platform.engine.TestExecutionResult;
import org.junit.platform.testkit.engine.EngineTestKit;
import org.junit.platform.testkit.engine.Event;
import org.junit.platform.testkit.engine.Events;
import org.opentest4j.AssertionFailedError;

/**
 * {@link DtronTest} as a user sees it: test classes of {@link LampCases} run through the JUnit Platform, with the
 * failed seeds and the reports in a folder of this test.
 */
class DtronTestTest {
    @TempDir
    Path dir;
    /** What the last tests run printed. */
    private String printed = "";

    @BeforeEach
    void intoThisTestsFolder() {
        System.setProperty(DtronExtension.SEED_FILE, dir.resolve("seeds.properties").toString());
        System.setProperty(DtronExtension.REPORT_DIRECTORY, dir.resolve("reports").toString());
    }

    @AfterEach
    void back() {
        System.clearProperty(DtronExtension.SEED_FILE);
        System.clearProperty(DtronExtension.REPORT_DIRECTORY);
    }

    @Test
    void theCorrectLampPassesOneTestPerSeedEachNamedByItsSeedWithItsReport() throws Exception {
        Events tests = run(LampCases.Correct.class);
        assertEquals(List.of("seed 100", "seed 101", "seed 102", "seed 103", "seed 104"), names(tests.started()));
        assertEquals(5, tests.succeeded().count(), () -> "every run passes: " + tests.failed().list());
        Path report = dir.resolve("reports").resolve(LampCases.Correct.class.getName()).resolve("lamp-seed-102.txt");
        String text = Files.readString(report);
        assertTrue(text.startsWith("dtron: lamp.xta, seed 102, 1000 time units of 1000 us in virtual time\n"), text);
        assertTrue(text.contains(" input press()\n") && text.contains(" output light(level=1)\n"), text);
        assertTrue(text.contains("\nPASSED: ") && text.contains("\ncoverage: locations 3/3"), text);
        String page = Files.readString(report.resolveSibling("lamp-seed-102.html"));
        assertTrue(page.contains("\"verdict\":{\"verdict\":\"PASSED\""), "the run's page, with its verdict");
        assertTrue(!Files.exists(dir.resolve("seeds.properties")), "no seed failed, none is stored");
    }

    @Test
    void theRunTakesTheTimeoutAndTimeUnitOfItsAnnotationAndGivesItsResult() throws Exception {
        Events tests = run(LampCases.Short.class);
        assertEquals(1, tests.succeeded().count(), () -> "the run passes: " + tests.failed().list());
        String text = Files.readString(dir.resolve("reports").resolve(LampCases.Short.class.getName())
                .resolve("lamp-seed-5.txt"));
        assertTrue(text.startsWith("dtron: lamp.xta, seed 5, 50 time units of 500 us in virtual time\n"), text);
    }

    @Test
    void virtualTimeFalseRunsOnTheWallClock() throws Exception {
        long start = System.nanoTime();
        Events tests = run(LampCases.RealTime.class);
        long millis = (System.nanoTime() - start) / 1_000_000;
        // no press can come before the timeout (the user waits 3 units): the run passes whatever the load
        assertEquals(1, tests.succeeded().count(), () -> "the run passes: " + tests.failed().list());
        assertTrue(millis >= 500, "2 units of 250 ms take at least 500 ms of wall time, not " + millis);
        String text = Files.readString(dir.resolve("reports").resolve(LampCases.RealTime.class.getName())
                .resolve("lamp-seed-1.txt"));
        assertTrue(text.startsWith("dtron: lamp.xta, seed 1, 2 time units of 250000 us in real time\n"), text);
    }

    @Test
    void aTronInterfaceFileOnTheClasspathGivesTheInterfaceTimeUnitAndTimeout() throws Exception {
        Events tests = run(LampCases.TronInterface.class);
        assertEquals(1, tests.succeeded().count(), () -> "the run passes: " + tests.failed().list());
        String text = Files.readString(dir.resolve("reports").resolve(LampCases.TronInterface.class.getName())
                .resolve("lamp-seed-3.txt"));
        assertTrue(text.startsWith("dtron: tron-lamp.xta, seed 3, 40 time units of 500 us in virtual time\n"), text);
        assertTrue(text.contains(" output light(level=1)\n"), text);
    }

    @Test
    void theLateLampFailsWithTheExplanationAndItsSeedsAreStored() throws Exception {
        Events tests = run(LampCases.Late.class);
        assertEquals(List.of("seed 7", "seed 8", "seed 9"), names(tests.started()));
        assertEquals(3, tests.failed().count());
        Throwable failure = thrown(tests.failed().list().get(0));
        assertInstanceOf(AssertionFailedError.class, failure);
        assertTrue(failure.getMessage().startsWith("FAILED with seed 7: no output came by t="), failure.getMessage());
        assertTrue(failure.getMessage().contains("The model allowed these outputs: light between t="),
                failure.getMessage());
        assertTrue(failure.getMessage().contains("the seed runs first next time"), failure.getMessage());
        assertEquals("7,8,9", stored().getProperty(LampCases.Late.class.getName() + "#lamp"));
        Path reports = dir.resolve("reports").resolve(LampCases.Late.class.getName());
        String report = Files.readString(reports.resolve("lamp-seed-8.txt"));
        assertTrue(report.contains("\nFAILED: no output came by t="), report);
        // the run's HTML page, as dtron run --report writes it: the verdict, the explanation, the model drawn
        assertTrue(failure.getMessage().endsWith(", its page: " + reports.resolve("lamp-seed-7.html") + ")"),
                failure.getMessage());
        String page = Files.readString(reports.resolve("lamp-seed-8.html"));
        assertTrue(page.startsWith("<!DOCTYPE html>"), page.substring(0, Math.min(100, page.length())));
        assertTrue(page.contains("\"verdict\":{\"verdict\":\"FAILED\",\"explanation\":\"no output came by t="),
                "the verdict and its explanation");
        assertTrue(page.contains("\"name\":\"Lamp\",\"auto\":true"), "the model, laid out automatically");
    }

    @Test
    void theSeedsOfTheRunsThatFailedRunFirstTheNextTime() {
        Events first = run(LampCases.LateNewSeeds.class);
        List<String> failed = names(first.failed());
        assertEquals(2, failed.size(), "the late lamp fails with every seed");
        assertTrue(printed.contains("dtron: FAILED with " + failed.get(0) + ": no output came by t="), printed);
        Events second = run(LampCases.LateNewSeeds.class);
        assertEquals(failed, names(second.started()).subList(0, 2), "last time's seeds come first, in their order");
        for (String seed : failed) {
            assertTrue(printed.contains("dtron: LateNewSeeds.lamp: " + seed + " did not pass last time; it runs first ("
                    + dir.resolve("seeds.properties") + ")\n"), printed);
        }
    }

    @Test
    void aStoredSeedThatPassesIsTakenOut() throws Exception {
        String key = LampCases.CorrectNewSeeds.class.getName() + "#lamp";
        Properties seeds = new Properties();
        seeds.setProperty(key, "4711");
        try (var out = Files.newBufferedWriter(dir.resolve("seeds.properties"))) {
            seeds.store(out, null);
        }
        Events tests = run(LampCases.CorrectNewSeeds.class);
        assertEquals("seed 4711", names(tests.started()).get(0));
        assertEquals(2, tests.succeeded().count());
        assertEquals(null, stored().getProperty(key), "the seed passed: it is no longer stored");
    }

    @Test
    void oneTestPerSeedAndGoalAGoalNoRunReachesIsAnErrorNotAFailure() throws Exception {
        Events tests = run(LampCases.Goals.class);
        assertEquals(List.of("seed 1, goal E<> Lamp.Switching and Lamp.level == 0", "seed 1, goal E<> User.u > 20",
                "seed 2, goal E<> Lamp.Switching and Lamp.level == 0", "seed 2, goal E<> User.u > 20"),
                names(tests.started()));
        assertEquals(List.of("seed 1, goal E<> Lamp.Switching and Lamp.level == 0",
                "seed 2, goal E<> Lamp.Switching and Lamp.level == 0"), names(tests.succeeded()));
        for (Event e : tests.failed().list()) {
            Throwable t = thrown(e);
            assertInstanceOf(Inconclusive.class, t, "INCONCLUSIVE is an error of the test, not an assertion");
            assertTrue(t.getMessage().startsWith("INCONCLUSIVE with seed "), t.getMessage());
        }
        String key = LampCases.Goals.class.getName() + "#lamp ";
        Properties stored = stored();
        assertEquals("1,2", stored.getProperty(key + "E<> User.u > 20"), "stored for the goal they did not reach");
        assertEquals(null, stored.getProperty(key + "E<> Lamp.Switching and Lamp.level == 0"));
    }

    @Test
    void mistakesInATestAreSaidClearly() {
        Events missing = runMethod(LampCases.Mistakes.class, "missingModel", DtronRun.class);
        String message = thrown(missing.failed().list().get(0)).getMessage();
        assertEquals("@DtronTest on Mistakes.missingModel: model 'no-such-lamp.xta' is neither a resource on the"
                + " classpath (io/dtron/junit/no-such-lamp.xta) nor a file (" + Path.of(System.getProperty("basedir",
                System.getProperty("user.dir"))).resolve("no-such-lamp.xta") + ")", message);

        Events broken = runMethod(LampCases.Mistakes.class, "brokenModel", DtronRun.class);
        String error = thrown(broken.failed().list().get(0)).getMessage();
        assertTrue(error.startsWith("@DtronTest on Mistakes.brokenModel: io/dtron/junit/broken.xta:2:"), error);
        assertTrue(error.contains("error: "), error);

        Events noRun = runMethod(LampCases.Mistakes.class, "noRun");
        assertTrue(thrown(noRun.failed().list().get(0)).getMessage().endsWith(": the method takes one parameter, a"
                + " DtronRun, and calls run.test(system), or, for systems behind bus adapters, a DtronBusRun, and"
                + " calls run.test(adapters)"));

        Events nothing = runMethod(LampCases.Mistakes.class, "testsNothing", DtronRun.class);
        assertTrue(thrown(nothing.failed().list().get(0)).getMessage().startsWith("the @DtronTest method returned"
                + " without testing: call run.test(system)"));
    }

    @Test
    void theCorrectLampBehindABusAdapterPassesInRealTimeOnAFreshBusOfItsOwn() throws Exception {
        int heldUp = LampBusAdapter.heldUp();
        Events tests = run(LampBusCases.Correct.class);
        assertEquals(List.of("seed 10", "seed 11"), names(tests.started()));
        for (Event failed : tests.failed().list()) {
            assertPassedUnlessHeldUp(thrown(failed), LampBusAdapter.heldUp() > heldUp);
        }
        Path reports = dir.resolve("reports").resolve(LampBusCases.Correct.class.getName());
        List<String> buses = new java.util.ArrayList<>();
        for (long seed : List.of(10L, 11L)) {
            String text = Files.readString(reports.resolve("lamp-seed-" + seed + ".txt"));
            String header = text.lines().findFirst().orElseThrow();
            assertTrue(header.matches("dtron: lamp\\.xta, seed " + seed + ", 40 time units of 50000 us in real time"
                    + " over bus 'dtron-junit-[0-9a-f]{8}' on 127\\.0\\.0\\.1"), header);
            buses.add(header.substring(header.indexOf(" over bus ")));
            if (names(tests.succeeded()).contains("seed " + seed)) {
                // the user presses by t=10 and the lamp shows its level within 2 units: both are in a run that passed
                assertTrue(text.contains(" input press()\n") && text.contains(" output light(level=1)\n"), text);
                assertTrue(text.contains("\nPASSED: "), text);
                assertTrue(Files.readString(reports.resolve("lamp-seed-" + seed + ".html")).contains(
                        "\"verdict\":{\"verdict\":\"PASSED\""), "the run's page, with its verdict");
            }
        }
        assertTrue(!buses.get(0).equals(buses.get(1)), "each run has a bus of its own: " + buses);
        if (tests.succeeded().count() == 2) {
            assertTrue(!Files.exists(dir.resolve("seeds.properties")), "no seed failed, none is stored");
        }
    }

    @Test
    void aBusRunSteeredTowardAGoalPassesWhenItIsReached() throws Exception {
        int heldUp = LampBusAdapter.heldUp();
        Events tests = run(LampBusCases.Goal.class);
        assertEquals(List.of("seed 5, goal E<> Lamp.Switching and Lamp.level == 0"), names(tests.started()));
        for (Event failed : tests.failed().list()) {
            assertPassedUnlessHeldUp(thrown(failed), LampBusAdapter.heldUp() > heldUp);
        }
        if (tests.succeeded().count() == 1) {
            String text = Files.readString(dir.resolve("reports").resolve(LampBusCases.Goal.class.getName())
                    .resolve("lamp-seed-5-goal-1.txt"));
            assertTrue(text.lines().findFirst().orElseThrow().startsWith("dtron: lamp.xta, seed 5, goal E<>"
                    + " Lamp.Switching and Lamp.level == 0, 100 time units of 50000 us in real time over bus '"), text);
            // the goal: the second press switches the lamp back to 0, after the first light
            assertTrue(text.contains(" output light(level=1)\n"), text);
            assertTrue(text.contains("\nPASSED: "), text);
        }
    }

    @Test
    void theCorrectLampPassesOverTheNatsServerOfTheSystemPropertyDtronNats() throws Exception {
        try (NatsServer nats = NatsServer.start(dir)) {
            System.setProperty(DtronExtension.NATS, " " + nats.url() + " ,");
            int heldUp = LampBusAdapter.heldUp();
            Events tests = run(LampBusCases.Correct.class);
            assertEquals(List.of("seed 10", "seed 11"), names(tests.started()));
            for (Event failed : tests.failed().list()) {
                assertPassedUnlessHeldUp(thrown(failed), LampBusAdapter.heldUp() > heldUp);
            }
            String header = Files.readString(dir.resolve("reports").resolve(LampBusCases.Correct.class.getName())
                    .resolve("lamp-seed-10.txt")).lines().findFirst().orElseThrow();
            assertTrue(header.matches(".* in real time over bus 'dtron-junit-[0-9a-f]{8}' on " + Pattern.quote(
                    nats.url())), header);
        } finally {
            System.clearProperty(DtronExtension.NATS);
        }
    }

    @Test
    void theLateLampBehindABusAdapterFailsWithTheExplanationAndItsSeedRunsFirstNextTime() throws Exception {
        Events first = run(LampBusCases.Late.class);
        assertEquals(1, first.failed().count(), () -> "the late lamp fails: " + printed);
        String seed = names(first.failed()).get(0);
        Throwable failure = thrown(first.failed().list().get(0));
        assertInstanceOf(AssertionFailedError.class, failure);
        // the deadline passes, or the light comes within the bus's reorder window after it, 3 units after the press
        assertTrue(failure.getMessage().startsWith("FAILED with " + seed + ": no output came by t=")
                || failure.getMessage().matches("(?s)FAILED with " + seed + ": output light\\(level=1\\) observed at"
                + " t=[0-9.]+ is too late: .*"), failure.getMessage());
        assertTrue(failure.getMessage().contains("The model allowed these outputs: light between t="),
                failure.getMessage());
        assertEquals(seed.substring("seed ".length()), stored().getProperty(LampBusCases.Late.class.getName()
                + "#lamp"));
        Events second = run(LampBusCases.Late.class);
        assertEquals(List.of(seed), names(second.started()), "the failed seed runs first (and alone: seeds = 1)");
        assertTrue(printed.contains("dtron: Late.lamp: " + seed + " did not pass last time; it runs first"), printed);
    }

    @Test
    void theLampInAJvmOfItsOwnJoinsTheRunsFreshBusByItsNameAndPasses() throws Exception {
        Events tests = run(LampBusCases.OtherProcess.class);
        assertEquals(List.of("seed 30"), names(tests.started()));
        String log = Files.readString(dir.resolve("reports").resolve("lamp-process.log"));
        Path reports = dir.resolve("reports").resolve(LampBusCases.OtherProcess.class.getName());
        String header = Files.readString(reports.resolve("lamp-seed-30.txt")).lines().findFirst().orElseThrow();
        String cluster = header.substring(header.indexOf("over bus '") + "over bus '".length(),
                header.indexOf("' on "));
        assertTrue(log.lines().anyMatch(line -> line.startsWith("lamp joined bus " + cluster + " as ")), log);
        for (Event failed : tests.failed().list()) {
            assertPassedUnlessHeldUp(thrown(failed), log.contains("this JVM was held up"));
        }
    }

    @Test
    void aSuiteWithoutDtronCoreIsToldToAddItWhenATestTakesADtronBusRun() throws Exception {
        String classpath = Stream.of(System.getProperty("java.class.path").split(File.pathSeparator))
                .filter(entry -> !entry.contains("dtron-core") && !entry.contains("jgroups"))
                .collect(Collectors.joining(File.pathSeparator));
        Process process = new ProcessBuilder(Path.of(System.getProperty("java.home"), "bin", "java").toString(), "-cp",
                classpath, WithoutCore.class.getName(), LampBusCases.Correct.class.getName())
                .redirectErrorStream(true).redirectOutput(dir.resolve("without-core.log").toFile()).start();
        assertTrue(process.waitFor(60, TimeUnit.SECONDS), "the JVM without dtron-core ends");
        String out = Files.readString(dir.resolve("without-core.log"));
        assertTrue(out.contains("failure: @DtronTest on Correct.lamp: a DtronBusRun tests over the DTRON bus, which"
                + " needs the artifact io.dtron:dtron-core on the test classpath: add it as a test dependency, of the"
                + " version of dtron-junit\n"), out);
    }

    @Test
    void aBusRunWithoutAnAdapterSaysWhichChannelsNoAdapterServed() {
        Events tests = run(LampBusCases.NoAdapter.class);
        Throwable error = thrown(tests.failed().list().get(0));
        assertInstanceOf(IllegalStateException.class, error);
        assertTrue(error.getMessage().matches("within 1000 ms no adapter on bus 'dtron-junit-[0-9a-f]{8}' on"
                + " 127\\.0\\.0\\.1 served input press, output light; no adapter said which channels it serves"
                + " \\(members: \\[.*\\]\\)"), error.getMessage());
    }

    /**
     * Fails unless {@code failure} of a run of the correct lamp over the bus is what a busy machine may cause: FAILED
     * on the light, when the lamp says it was held up past its tolerance ({@code heldUp}: {@link
     * LampBusAdapter#heldUp()} grew, or the lamp's JVM said so); or INCONCLUSIVE, when the tester says it was held up
     * (its input came too late, or an event reached it later than the reorder window allows).
     */
    private static void assertPassedUnlessHeldUp(Throwable failure, boolean heldUp) {
        String message = failure.getMessage();
        if (failure instanceof AssertionFailedError) {
            assertTrue(message.matches("(?s)FAILED with seed \\d+: (output light.* is too late|no output came by).*"),
                    message);
            assertTrue(heldUp, "a FAILED correct lamp that was not late: " + message);
        } else {
            assertInstanceOf(Inconclusive.class, failure, message);
            assertTrue(message.matches("(?s)INCONCLUSIVE with seed \\d+: .*(\\((input executed too late|too late for"
                    + " the window the environment allowed)\\)|more than the reorder window).*"), message);
        }
    }

    /** Runs the test class's tests; what they print goes to {@link #printed}. */
    private Events run(Class<?> testClass) {
        return printing(() -> EngineTestKit.engine("junit-jupiter").selectors(selectClass(testClass)).execute()
                .testEvents());
    }

    private Events runMethod(Class<?> testClass, String method, Class<?>... parameters) {
        return printing(() -> EngineTestKit.engine("junit-jupiter").selectors(selectMethod(testClass, method,
                parameters.length == 0 ? "" : parameters[0].getName())).execute().allEvents());
    }

    private Events printing(java.util.function.Supplier<Events> tests) {
        PrintStream out = System.out;
        ByteArrayOutputStream bytes = new ByteArrayOutputStream();
        System.setOut(new PrintStream(bytes, true, StandardCharsets.UTF_8));
        try {
            return tests.get();
        } finally {
            System.setOut(out);
            printed = bytes.toString(StandardCharsets.UTF_8);
        }
    }

    private static List<String> names(Events events) {
        return events.map(e -> e.getTestDescriptor().getDisplayName()).toList();
    }

    private static Throwable thrown(Event event) {
        return event.getPayload(TestExecutionResult.class).flatMap(TestExecutionResult::getThrowable).orElseThrow();
    }

    private Properties stored() throws Exception {
        Properties p = new Properties();
        try (Reader in = Files.newBufferedReader(dir.resolve("seeds.properties"))) {
            p.load(in);
        }
        return p;
    }
}
