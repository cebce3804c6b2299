package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageProjects;
import io.dtron.testsupport.ShellWords;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.w3c.dom.Element;
import org.w3c.dom.NodeList;

/**
 * The JUnit 5 example of {@code junit.md} in a fresh Maven project: the page's {@code pom.xml} (depending on
 * {@code io.dtron:dtron-junit} as this build installed it, and nothing of this build's own poms), its model and its
 * classes, built with the page's {@code mvn test} by the {@code mvn} on the {@code PATH}, twice. The lamp passes its
 * 20 seeds in virtual time, each test named by its seed in Surefire's XML; the late lamp fails every seed with the
 * explanation, and the second time its failed seeds run first. Then the page's {@code dtron run --junit} in that
 * project (compared with what the page shows) and Surefire's report plugin, whose page lists the JUnit 5 tests and
 * the run of {@code dtron run} by their names. Runs after {@code mvn install} has installed dtron-junit and the jar
 * is built.
 */
@Timeout(value = 600, unit = TimeUnit.SECONDS)
class JunitPageIT {
    private static final Path JAR = Path.of("target", "dtron.jar").toAbsolutePath();
    private static final Pattern LAMP_TEST = Pattern.compile("lamp\\(DtronRun\\) seed (\\d+)");
    private static final Pattern LATE_TEST = Pattern.compile("lateLamp\\(DtronRun\\) seed (\\d+)");

    @TempDir
    static Path dir;
    private static Path repository;
    private static DocPage page;
    private static Path project;
    /** What each {@code mvn test} printed, and Surefire's reports of the two test classes after it. */
    private static final List<Build> builds = new ArrayList<>();

    private record Build(String output, Element lamp, Element late) {
    }

    @BeforeAll
    static void buildTheProjectOfThePageTwice() throws Exception {
        repository = PageProjects.requireInstalled("dtron-junit");
        page = DocPage.read("junit.md");
        project = Files.createDirectories(dir.resolve("lamp"));
        String pom = page.block("xml", "<project");
        assertTrue(pom.contains("<artifactId>dtron-junit</artifactId>\n      <version>" + PageProjects.version()
                + "</version>"), "the page's pom depends on this build's dtron-junit");
        assertTrue(!pom.contains("<parent>"), "the page's project has no parent");
        Files.writeString(project.resolve("pom.xml"), pom);
        Path tests = Files.createDirectories(project.resolve("src/test/java"));
        for (String name : List.of("Lamp", "LampTest", "LateLampTest")) {
            Files.writeString(tests.resolve(name + ".java"), javaClass(name));
        }
        Path resources = Files.createDirectories(project.resolve("src/test/resources"));
        Files.writeString(resources.resolve("lamp.xta"), page.blockAfter("The model, `lamp.xta`").code());
        List<String> mvnTest = command("$ mvn test");
        for (int i = 1; i <= 2; i++) {
            try (ChildProcess mvn = ChildProcess.start(project, dir.resolve("mvn-test-" + i + ".log"), mvnTest)) {
                int exit = mvn.waitFor(PageProjects.BUILD);
                String output = mvn.output();
                assertEquals(1, exit, "mvn test fails, on the late lamp; it printed:\n" + output);
                builds.add(new Build(output, report("LampTest"), report("LateLampTest")));
            }
        }
    }

    @Test
    void theLampPassesTwentySeedsInVirtualTimeEachTestNamedByItsSeed() {
        for (Build build : builds) {
            assertEquals(List.of("20", "0", "0"), counts(build.lamp()), build.output());
            List<String> seeds = seeds(build.lamp(), LAMP_TEST);
            assertEquals(20, new HashSet<>(seeds).size(), "20 tests, each with a seed of its own: " + seeds);
        }
    }

    @Test
    void noPartOfTheBusIsOnTheClasspathOfASuiteThatDependsOnDtronJunitAlone() {
        String classpath = property(builds.get(0).lamp(), "surefire.test.class.path");
        assertTrue(classpath.contains("dtron-junit-" + PageProjects.version() + ".jar"), classpath);
        for (String bus : List.of("dtron-core", "dtron-api", "jgroups", "jnats", "protobuf-java")) {
            assertTrue(!classpath.contains("/" + bus + "-"), "dtron-core is optional: no " + bus + " on " + classpath);
        }
    }

    /** The value of a property in the {@code properties} of a suite of Surefire's XML report. */
    static String property(Element suite, String name) {
        NodeList properties = suite.getElementsByTagName("property");
        for (int i = 0; i < properties.getLength(); i++) {
            Element property = (Element) properties.item(i);
            if (property.getAttribute("name").equals(name)) {
                return property.getAttribute("value");
            }
        }
        throw new AssertionError("Surefire's report has no property " + name);
    }

    @Test
    void theLateLampFailsWithTheExplanationAndItsSeedsComeFirstTheNextTime() throws Exception {
        Build first = builds.get(0);
        Build second = builds.get(1);
        assertEquals(List.of("5", "5", "0"), counts(first.late()), first.output());
        List<String> failed = seeds(first.late(), LATE_TEST);
        NodeList failures = first.late().getElementsByTagName("failure");
        List<String> shown = page.blockAfter("each failure saying why, with the seed:").code().lines().toList();
        for (int i = 0; i < failures.getLength(); i++) {
            String message = ((Element) failures.item(i)).getAttribute("message");
            assertTrue(message.startsWith("FAILED with seed " + failed.get(i) + ": no output came by t="), message);
            List<String> lines = message.lines().toList();
            assertEquals(shown.size(), lines.size(), "the failure has the lines the page shows: " + message);
            for (int l = 0; l < lines.size(); l++) {
                assertTrue(pattern(shown.get(l), true).matcher(lines.get(l)).matches(), "the failure is as the page"
                        + " shows it, but for its numbers and folders: '" + shown.get(l) + "' is '" + lines.get(l)
                        + "'");
            }
            assertTrue(message.contains("(the seed runs first next time, from " + project.resolve(
                    ".dtron/failed-seeds.properties")), message);
        }
        assertEquals(failed, seeds(second.late(), LATE_TEST), "the seeds that failed run first, in their order");
        assertTrue(second.output().contains("dtron: LateLampTest.lateLamp: seed " + failed.get(0) + " did not pass last"
                + " time; it runs first"), second.output());
        assertTrue(Files.readString(project.resolve("target/dtron-reports/LateLampTest/lateLamp-seed-" + failed.get(0)
                + ".txt")).contains("\nFAILED: no output came by t="));
        assertTrue(Files.readString(project.resolve("target/dtron-reports/LateLampTest/lateLamp-seed-" + failed.get(0)
                + ".html")).contains("\"verdict\":{\"verdict\":\"FAILED\",\"explanation\":\"no output came by t="),
                "the run's page");
    }

    @Test
    void theJunitXmlOfDtronRunIsReadBySurefiresReportPluginWithTheTestsOfJunit5() throws Exception {
        DocPage.Block session = page.blocksStartingWith("$ java -jar dtron.jar run ").stream().findFirst()
                .orElseThrow(() -> new AssertionError("junit.md shows no dtron run --junit"));
        List<String> lines = new ArrayList<>(session.code().lines().toList());
        List<String> words = new ArrayList<>(ShellWords.split(lines.remove(0).substring(2)));
        words.set(0, ChildProcess.tool("java"));
        Files.copy(JAR, project.resolve("dtron.jar"));
        String xml = words.get(words.indexOf("--junit") + 1);
        try (ChildProcess run = ChildProcess.start(project, dir.resolve("dtron-run.log"), words)) {
            assertEquals(2, run.waitFor(Duration.ofSeconds(60)), run.output());
            List<String> out = run.output().lines().toList();
            assertEquals(lines.size(), out.size(), "the lines the page shows:\n" + run.output());
            for (int i = 0; i < lines.size(); i++) {
                assertTrue(pattern(lines.get(i), false).matcher(out.get(i)).matches(), "junit.md line " + session.line()
                        + ": '" + lines.get(i) + "' was printed as '" + out.get(i) + "'");
            }
        }
        Element suite = JunitReportTest.parse(project.resolve(xml)).getDocumentElement();
        assertEquals(List.of("1", "1", "0"), counts(suite));

        ChildProcess.run(project, dir.resolve("mvn-report.log"), PageProjects.BUILD,
                command("$ mvn org.apache.maven.plugins:maven-surefire-report-plugin"));
        String html = Files.readString(project.resolve("target/reports/surefire.html"));
        assertTrue(page.text().contains("`target/reports/surefire.html` lists `Lamp:late, seed 1`"));
        assertTrue(html.contains(">Lamp:late, seed 1</a>"), "the report lists dtron run's test case by its name");
        for (String seed : seeds(builds.get(1).lamp(), LAMP_TEST)) {
            assertTrue(html.contains(">lamp(DtronRun) seed " + seed + "<"), "the report lists seed " + seed);
        }
        assertTrue(html.contains("no output came by t="), "the report shows the failures' explanations");
    }

    /** The page's one session that starts with {@code start}, its first line as a command for this build's Maven. */
    private static List<String> command(String start) {
        return command(page, repository, start);
    }

    /**
     * The one session of {@code page} that starts with {@code start}, its first line as a command for the Maven on
     * the {@code PATH} with {@code repository} as its local repository.
     */
    static List<String> command(DocPage page, Path repository, String start) {
        List<DocPage.Block> blocks = page.blocksStartingWith(start);
        assertEquals(1, blocks.size(), "junit.md should have one session starting with '" + start + "'");
        List<String> words = ShellWords.split(blocks.get(0).code().lines().findFirst().orElseThrow().substring(2));
        List<String> command = new ArrayList<>(List.of(ChildProcess.mvn(), "-B",
                "-Dmaven.repo.local=" + repository));
        command.addAll(words.subList(1, words.size()));
        return command;
    }

    private static String javaClass(String name) {
        return javaClass(page, name);
    }

    /** The one java block of {@code page} that declares class {@code name}. */
    static String javaClass(DocPage page, String name) {
        Pattern declaration = Pattern.compile("(?m)^(public )?class " + name + "\\b");
        List<String> found = page.blocks("java").stream().filter(b -> declaration.matcher(b).find()).toList();
        assertEquals(1, found.size(), "junit.md should declare class " + name + " once");
        return found.get(0);
    }

    private static Element report(String testClass) throws Exception {
        return report(project, testClass);
    }

    /** Surefire's XML report of {@code testClass} in {@code project}. */
    static Element report(Path project, String testClass) throws Exception {
        return JunitReportTest.parse(project.resolve("target/surefire-reports/TEST-" + testClass + ".xml"))
                .getDocumentElement();
    }

    /** A suite's numbers of tests, failures and errors. */
    static List<String> counts(Element suite) {
        return List.of(suite.getAttribute("tests"), suite.getAttribute("failures"), suite.getAttribute("errors"));
    }

    /** The seeds in the names of the suite's test cases, in their order; every name must match {@code name}. */
    static List<String> seeds(Element suite, Pattern name) {
        List<String> seeds = new ArrayList<>();
        NodeList cases = suite.getElementsByTagName("testcase");
        for (int i = 0; i < cases.getLength(); i++) {
            String test = ((Element) cases.item(i)).getAttribute("name");
            Matcher m = name.matcher(test);
            assertTrue(m.matches(), "a test named by its seed: " + test);
            seeds.add(m.group(1));
        }
        return seeds;
    }

    /** A line of the page as a pattern: "..." is any text, and with {@code anyNumber} a number any number. */
    private static Pattern pattern(String line, boolean anyNumber) {
        StringBuilder regex = new StringBuilder();
        Matcher m = Pattern.compile(anyNumber ? "\\.\\.\\.|\\d+" : "\\.\\.\\.").matcher(line);
        int last = 0;
        while (m.find()) {
            regex.append(Pattern.quote(line.substring(last, m.start())))
                    .append(m.group().equals("...") ? ".*" : "\\d+");
            last = m.end();
        }
        return Pattern.compile(regex.append(Pattern.quote(line.substring(last))).toString());
    }
}
