package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageProjects;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.TimeUnit;
import java.util.regex.Pattern;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.w3c.dom.Element;
import org.w3c.dom.NodeList;

/**
 * The bus example of {@code junit.md} in a fresh Maven project: the page's {@code pom.xml} with the page's {@code
 * dtron-core} dependency added to its dependencies (nothing of this build's own poms), the model, the bus adapter and
 * the two tests of the page, built with the page's {@code mvn test} by the {@code mvn} on the {@code PATH}, twice.
 * The lamp behind its bus adapter passes its 3 seeds in real time (unless the machine held it up, which it says),
 * each run on a bus of its own; the late lamp fails
 * each of its 2 seeds with the explanation, and the second time its failed seeds run first. Runs after {@code mvn
 * install} has installed dtron-junit and dtron-core.
 */
@Timeout(value = 600, unit = TimeUnit.SECONDS)
class JunitBusPageIT {
    private static final Pattern LAMP_TEST = Pattern.compile("lamp\\(DtronBusRun\\) seed (\\d+)");
    private static final Pattern LATE_TEST = Pattern.compile("lateLamp\\(DtronBusRun\\) seed (\\d+)");
    private static final Pattern BUS = Pattern.compile(" in real time over bus 'dtron-junit-[0-9a-f]{8}' on"
            + " 127\\.0\\.0\\.1");

    @TempDir
    static Path dir;
    private static Path project;
    /** What each {@code mvn test} printed, and Surefire's reports of the two test classes after it. */
    private static final List<Build> builds = new ArrayList<>();

    private record Build(String output, Element lamp, Element late) {
    }

    @BeforeAll
    static void buildTheBusProjectOfThePageTwice() throws Exception {
        Path repository = PageProjects.requireInstalled("dtron-junit");
        PageProjects.requireInstalled("dtron-core");
        DocPage page = DocPage.read("junit.md");
        project = Files.createDirectories(dir.resolve("lamp-bus"));
        String pom = page.block("xml", "<project");
        String dependency = page.block("xml", "<artifactId>dtron-core</artifactId>");
        assertTrue(dependency.contains("<version>" + PageProjects.version() + "</version>"), dependency);
        assertTrue(pom.contains("\n  </dependencies>"), pom);
        Files.writeString(project.resolve("pom.xml"), pom.replace("\n  </dependencies>", "\n"
                + dependency.stripTrailing() + "\n  </dependencies>"));
        Path tests = Files.createDirectories(project.resolve("src/test/java"));
        for (String name : List.of("LampBusAdapter", "LampBusTest", "LateLampBusTest")) {
            Files.writeString(tests.resolve(name + ".java"), JunitPageIT.javaClass(page, name));
        }
        Path resources = Files.createDirectories(project.resolve("src/test/resources"));
        Files.writeString(resources.resolve("lamp.xta"), page.blockAfter("The model, `lamp.xta`").code());
        List<String> mvnTest = JunitPageIT.command(page, repository, "$ mvn test");
        for (int i = 1; i <= 2; i++) {
            try (ChildProcess mvn = ChildProcess.start(project, dir.resolve("mvn-test-" + i + ".log"), mvnTest)) {
                int exit = mvn.waitFor(PageProjects.BUILD);
                String output = mvn.output();
                assertEquals(1, exit, "mvn test fails, on the late lamp; it printed:\n" + output);
                builds.add(new Build(output, JunitPageIT.report(project, "LampBusTest"),
                        JunitPageIT.report(project, "LateLampBusTest")));
            }
        }
    }

    @Test
    void theLampBehindItsBusAdapterPassesEveryRunOnABusOfItsOwn() throws Exception {
        for (Build build : builds) {
            List<String> seeds = JunitPageIT.seeds(build.lamp(), LAMP_TEST);
            assertEquals(3, new HashSet<>(seeds).size(), "3 tests, each with a seed of its own: " + seeds);
            assertEquals("0", build.lamp().getAttribute("errors"), build.output());
            NodeList failures = build.lamp().getElementsByTagName("failure");
            for (int i = 0; i < failures.getLength(); i++) {
                // in real time a busy machine may hold the lamp up: then, and only then, it fails, and the lamp says so
                String message = ((Element) failures.item(i)).getAttribute("message");
                assertTrue(message.matches("(?s)FAILED with seed \\d+: (output light.* is too late|no output came"
                        + " by).*"), message);
                assertTrue(build.output().contains("this JVM was held up"), "a FAILED correct lamp that was not"
                        + " late: " + message + "\n" + build.output());
            }
        }
        Set<String> buses = new HashSet<>();
        for (String seed : JunitPageIT.seeds(builds.get(1).lamp(), LAMP_TEST)) {
            String first = Files.readString(project.resolve("target/dtron-reports/LampBusTest/lamp-seed-" + seed
                    + ".txt")).lines().findFirst().orElseThrow();
            assertTrue(first.startsWith("dtron: lamp.xta, seed " + seed + ", 30 time units of 100000 us"), first);
            assertTrue(BUS.matcher(first).find(), first);
            buses.add(first.substring(first.indexOf(" over bus ")));
        }
        assertEquals(3, buses.size(), "each run on a bus of its own: " + buses);
        String classpath = JunitPageIT.property(builds.get(0).lamp(), "surefire.test.class.path");
        assertTrue(classpath.contains("/dtron-core-" + PageProjects.version() + ".jar"), classpath);
    }

    @Test
    void theLateLampFailsWithTheExplanationAndItsSeedsComeFirstTheNextTime() throws Exception {
        Build first = builds.get(0);
        assertEquals(List.of("2", "2", "0"), JunitPageIT.counts(first.late()), first.output());
        List<String> failed = JunitPageIT.seeds(first.late(), LATE_TEST);
        NodeList failures = first.late().getElementsByTagName("failure");
        for (int i = 0; i < failures.getLength(); i++) {
            String message = ((Element) failures.item(i)).getAttribute("message");
            // the deadline passed, or the light came within the bus's reorder window after it
            assertTrue(message.startsWith("FAILED with seed " + failed.get(i) + ": no output came by t=")
                    || message.matches("(?s)FAILED with seed " + failed.get(i) + ": output light\\(level=1\\) observed"
                    + " at t=[0-9.]+ is too late: The model allowed these outputs: light between t=.*"), message);
            assertTrue(message.contains("(the seed runs first next time, from " + project.resolve(
                    ".dtron/failed-seeds.properties")), message);
        }
        Build second = builds.get(1);
        assertEquals(failed, JunitPageIT.seeds(second.late(), LATE_TEST), "the seeds that failed run first, in order");
        assertTrue(second.output().contains("dtron: LateLampBusTest.lateLamp: seed " + failed.get(0) + " did not pass"
                + " last time; it runs first"), second.output());
        String report = Files.readString(project.resolve("target/dtron-reports/LateLampBusTest/lateLamp-seed-"
                + failed.get(0) + ".txt"));
        assertTrue(report.contains("\nFAILED: "), report);
    }
}
