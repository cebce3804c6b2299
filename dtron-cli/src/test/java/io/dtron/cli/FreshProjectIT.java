package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageProjects;
import java.io.File;
import java.io.StringReader;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import javax.xml.parsers.DocumentBuilderFactory;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.w3c.dom.Document;
import org.w3c.dom.Element;
import org.w3c.dom.Node;
import org.w3c.dom.NodeList;
import org.xml.sax.InputSource;

/**
 * Depending on DTRON as the documentation says: the complete adapter of {@code adapters.md}, taken from the page,
 * is built in an empty folder with the page's {@code pom.xml} as it is (the {@code mvn} on the {@code PATH}, with the
 * page's command, against the {@code io.dtron:dtron-api} this build installed into the local repository and Maven
 * Central for the rest: nothing of the build's own poms) and with plain {@code javac} against {@code dtron.jar}; each
 * build runs in a JVM of its own against {@code java -jar dtron.jar MODEL} in another, and the run must pass.
 *
 * <p>The build passes the local repository and the project's version as system properties
 * ({@code dtron.localRepository}, {@code dtron.version}); the test runs after the jar is built, and needs
 * {@code mvn install} (the README's test command), so that dtron-api is installed before it runs.
 */
@Timeout(value = 300, unit = TimeUnit.SECONDS)
class FreshProjectIT {
    private static final Path JAR = Path.of("target", "dtron.jar").toAbsolutePath();
    /** The project's folder, where the page's commands run. */
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    /** How the page's tester command starts. */
    private static final String TESTER = "$ java -jar dtron-cli/target/dtron.jar ";
    private static final Duration RUN = Duration.ofSeconds(90);
    /** The command the page gives for building the adapter's project and writing its classpath. */
    private static final String MVN_BUILD = "mvn -q compile dependency:build-classpath"
            + " -Dmdep.outputFile=target/classpath.txt";

    @TempDir
    Path dir;

    private final String cluster = "fresh-" + UUID.randomUUID().toString().substring(0, 8);

    @Test
    void theAdapterOfThePageBuiltWithMavenFromAFreshProjectPasses() throws Exception {
        String version = PageProjects.version();
        Path repository = PageProjects.requireInstalled("dtron-api");
        DocPage page = DocPage.read("adapters.md");
        assertTrue(page.text().contains(MVN_BUILD), page + " should build the adapter with '" + MVN_BUILD + "'");

        Path project = Files.createDirectories(dir.resolve("ticker-adapter"));
        Files.writeString(project.resolve("pom.xml"), pagePom(page, version));
        Path sources = Files.createDirectories(project.resolve("src/main/java"));
        Files.writeString(sources.resolve("TickerAdapter.java"), adapterSource(page));

        long start = System.nanoTime();
        List<String> build = new ArrayList<>(List.of(ChildProcess.mvn(), "-B", "-Dmaven.repo.local=" + repository));
        build.addAll(List.of(MVN_BUILD.split(" ")).subList(1, MVN_BUILD.split(" ").length));
        ChildProcess.run(project, dir.resolve("mvn.log"), PageProjects.BUILD, build);
        System.out.printf("FreshProjectIT: mvn compile dependency:build-classpath took %d ms%n",
                (System.nanoTime() - start) / 1_000_000);
        String classpath = Files.readString(project.resolve("target/classpath.txt")).trim();
        assertTrue(classpath.contains("dtron-api-" + version + ".jar"), "the classpath Maven wrote: " + classpath);

        runAgainstTheTester(project, "target/classes" + File.pathSeparator + classpath);
    }

    @Test
    void theAdapterOfThePageCompiledWithJavacAgainstDtronJarPasses() throws Exception {
        DocPage page = DocPage.read("adapters.md");
        assertTrue(page.text().contains("javac -cp dtron-cli/target/dtron.jar TickerAdapter.java"),
                page + " should compile the adapter with javac against dtron.jar");
        Path folder = Files.createDirectories(dir.resolve("javac"));
        Files.writeString(folder.resolve("TickerAdapter.java"), adapterSource(page));
        ChildProcess.run(folder, dir.resolve("javac.log"), PageProjects.BUILD,
                List.of(ChildProcess.tool("javac"), "-cp", JAR.toString(), "TickerAdapter.java"));

        runAgainstTheTester(folder, JAR + File.pathSeparator + ".");
    }

    @Test
    void theReadmeAndThePageGiveThisBuildsCoordinates() throws Exception {
        String coordinates = "io.dtron:dtron-api:" + PageProjects.version();
        String readme = Files.readString(Path.of("..", "README.md"));
        assertTrue(readme.contains(coordinates), "README.md should give the coordinates " + coordinates);
        assertTrue(DocPage.read("adapters.md").text().contains(coordinates), "adapters.md should give " + coordinates);
    }

    /**
     * Starts the page's tester command in the project's folder (on this test's bus), then the adapter in
     * {@code folder} with {@code classpath}; the run must pass.
     */
    private void runAgainstTheTester(Path folder, String classpath) throws Exception {
        List<String> tester = testerCommand(DocPage.read("adapters.md"));
        String timeout = tester.get(tester.indexOf("--timeout") + 1);
        long start = System.nanoTime();
        String dtronLatency;
        try (ChildProcess dtron = ChildProcess.start(ROOT, dir.resolve("dtron.log"), tester);
                ChildProcess adapter = ChildProcess.java(folder, dir.resolve("adapter.log"),
                        List.of("-cp", classpath, "TickerAdapter"))) {
            int exit = dtron.waitFor(RUN);
            String out = dtron.output();
            String both = "dtron.jar printed:\n" + out + "\nthe adapter printed:\n" + adapter.output();
            assertEquals(0, exit, "dtron.jar should pass the adapter; " + both);
            assertTrue(out.contains("ticker-adapter"), "the adapter joined the bus; " + both);
            assertTrue(out.contains("PASSED: the timeout of " + timeout + " time units was reached after "), both);
            assertEquals(0, adapter.waitFor(RUN), "the adapter leaves when the tester has left; " + both);
            dtronLatency = out.lines().filter(l -> l.startsWith("latency t2 - t1 of outputs")).findFirst().orElse("");
        }
        System.out.printf("FreshProjectIT: tester and adapter took %d ms; %s%n", (System.nanoTime() - start) / 1_000_000,
                dtronLatency);
    }

    /**
     * The page's tester command (its first line and the lines it continues onto), with this JDK's {@code java} and
     * this test's bus instead of {@code lab}.
     */
    private List<String> testerCommand(DocPage page) {
        String session = page.blocksStartingWith(TESTER).stream().findFirst()
                .orElseThrow(() -> new AssertionError(page + " should start the tester with '" + TESTER + "'"))
                .code();
        StringBuilder command = new StringBuilder();
        for (String line : session.split("\n")) {
            command.append(line).append(' ');
            if (!line.endsWith("\\")) {
                break;
            }
            command.setLength(command.length() - 2);
        }
        List<String> words = new ArrayList<>(List.of(command.substring(2).trim().split("\\s+")));
        assertTrue(words.contains("lab"), "the page's tester uses cluster lab: " + words);
        words.replaceAll(w -> w.equals("lab") ? cluster : w);
        words.set(0, ChildProcess.tool("java"));
        return words;
    }

    /** The page's adapter, on this test's own bus cluster instead of the page's {@code lab}, to run beside others. */
    private String adapterSource(DocPage page) {
        String source = page.javaClass("TickerAdapter");
        String lab = ".clusterName(\"lab\")";
        if (source.indexOf(lab) < 0 || source.indexOf(lab) != source.lastIndexOf(lab)) {
            fail(page + ": the adapter should join cluster 'lab' once, with " + lab + ", as the page's commands say;"
                    + " the test puts its own cluster there");
        }
        return source.replace(lab, ".clusterName(\"" + cluster + "\")");
    }

    /** The page's {@code pom.xml}, as it is: the xml block with a {@code <project>}; it must depend on this build's dtron-api. */
    private static String pagePom(DocPage page, String version) throws Exception {
        String text = page.block("xml", "<project");
        Document pom = parse(text);
        NodeList dependencies = pom.getElementsByTagName("dependency");
        for (int i = 0; i < dependencies.getLength(); i++) {
            Element dependency = (Element) dependencies.item(i);
            if (text(dependency, "groupId").equals("io.dtron") && text(dependency, "artifactId").equals("dtron-api")) {
                assertEquals(version, text(dependency, "version"), page + ": the pom's dtron-api is not this build's");
                return text;
            }
        }
        throw new AssertionError(page + ": the pom.xml has no dependency on io.dtron:dtron-api");
    }

    private static Document parse(String xml) throws Exception {
        return DocumentBuilderFactory.newInstance().newDocumentBuilder().parse(new InputSource(new StringReader(xml)));
    }

    /** The text of {@code element}'s direct child {@code name}, or "" without one. */
    private static String text(Element element, String name) {
        for (Node child = element.getFirstChild(); child != null; child = child.getNextSibling()) {
            if (child instanceof Element e && e.getTagName().equals(name)) {
                return e.getTextContent().trim();
            }
        }
        return "";
    }
}
