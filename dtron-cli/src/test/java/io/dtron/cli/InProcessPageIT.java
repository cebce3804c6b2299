package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageProjects;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The examples of {@code in-process.md} do what the page says: the model and the system under test are taken from
 * the page into an empty folder, with {@code dtron.jar}, and the page's sessions (the lines after {@code $ }) are run
 * command by command, once with {@code javac} and once in the page's Maven project (its {@code pom.xml} as it is, the
 * {@code mvn} on the {@code PATH}); each command must print what the page shows after it (compared with runs of
 * blanks made one, so that the page may wrap long lines) and exit as its verdict says. Runs after the jar is built,
 * the Maven project after {@code mvn install} has installed dtron-engine.
 */
@Timeout(value = 180, unit = TimeUnit.SECONDS)
class InProcessPageIT {
    private static final Path JAR = Path.of("target", "dtron.jar").toAbsolutePath();
    private static final Duration COMMAND = Duration.ofSeconds(60);

    @TempDir
    Path dir;
    /** The local Maven repository the page's {@code mvn} commands use. */
    private Path repository;

    /** One command of the session and the output the page shows for it. */
    private record Step(String command, String output) {
    }

    @Test
    void theEchoOfThePagePassesInVirtualTimeAndItsLateVariantFailsAsThePageShows() throws Exception {
        DocPage page = DocPage.read("in-process.md");
        Files.writeString(dir.resolve("echo.xta"), page.blockAfter("The model, `echo.xta`").code());
        Files.writeString(dir.resolve("EchoSystem.java"), page.javaClass("EchoSystem"));
        Files.copy(JAR, dir.resolve("dtron.jar"));

        assertEquals(List.of("PASSED EchoSystem", "FAILED EchoSystem:late"), runSession(page, "$ javac", dir),
                "the page shows the correct echo passing and the late one failing");
    }

    /**
     * The Maven project of the page: its {@code pom.xml} as it is, built with the page's command by the {@code mvn}
     * on the {@code PATH} (against the dtron-engine this build installed, and Maven Central), and its classes tested
     * as the page shows.
     */
    @Test
    void theMavenProjectOfThePageBuildsAndItsEchoPasses() throws Exception {
        Path repository = PageProjects.requireInstalled("dtron-engine");
        DocPage page = DocPage.read("in-process.md");
        Path project = Files.createDirectories(dir.resolve("echo"));
        Files.writeString(project.resolve("pom.xml"), page.block("xml", "<project"));
        Path sources = Files.createDirectories(project.resolve("src/main/java"));
        Files.writeString(sources.resolve("EchoSystem.java"), page.javaClass("EchoSystem"));
        Files.writeString(project.resolve("echo.xta"), page.blockAfter("The model, `echo.xta`").code());
        Files.copy(JAR, project.resolve("dtron.jar"));

        this.repository = repository;
        assertEquals(List.of("PASSED EchoSystem"), runSession(page, "$ mvn", project));
    }

    /**
     * Runs the one session of the page that starts with {@code start} in {@code folder}, command by command, and
     * returns the verdict of each run with its system under test.
     */
    private List<String> runSession(DocPage page, String start, Path folder) throws Exception {
        List<DocPage.Block> sessions = page.blocksStartingWith(start);
        assertEquals(1, sessions.size(), page + " should show one session starting with '" + start + "'");
        List<String> verdicts = new ArrayList<>();
        for (Step step : steps(sessions.get(0).code())) {
            List<String> words = List.of(step.command().trim().split("\\s+"));
            int expectedExit = 0;
            if (words.get(0).equals("java")) {
                assertTrue(step.command().contains("--virtual-time"), "the page's runs are in virtual time: "
                        + step.command());
                String verdict = verdictIn(step.output(), step.command());
                verdicts.add(verdict + " " + words.get(words.indexOf("--sut") + 1));
                expectedExit = switch (verdict) {
                    case "PASSED" -> 0;
                    case "FAILED" -> 2;
                    default -> 3;
                };
            }
            run(folder, step, words, expectedExit);
        }
        return verdicts;
    }

    /** Runs a step's command in the folder (java and javac of this JDK) and compares its output with the page's. */
    private void run(Path folder, Step step, List<String> words, int expectedExit) throws Exception {
        List<String> command = new ArrayList<>();
        switch (words.get(0)) {
            // the build's local repository (this build's dtron-engine, and Central for the rest); nothing else
            case "mvn" -> command.addAll(List.of(ChildProcess.mvn(), "-B", "-Dmaven.repo.local=" + repository));
            case "java" -> {
                command.add(ChildProcess.tool("java"));
                command.addAll(ChildProcess.FAST_JVM);
            }
            case "javac" -> command.add(ChildProcess.tool("javac"));
            default -> fail("the page's sessions run only mvn, java and javac, not: " + step.command());
        }
        command.addAll(words.subList(1, words.size()));
        try (ChildProcess child = ChildProcess.start(folder, dir.resolve("command.log"), command)) {
            int exit = child.waitFor(words.get(0).equals("mvn") ? PageProjects.BUILD : COMMAND);
            String output = child.output();
            String context = "'" + step.command() + "' printed:\n" + output;
            assertEquals(expectedExit, exit, "the exit code; " + context);
            assertEquals(oneLine(step.output()), oneLine(output), "the page shows another output; " + context);
        }
    }

    /** The verdict (PASSED, FAILED, INCONCLUSIVE) the page shows for a run. */
    private static String verdictIn(String output, String command) {
        for (String verdict : List.of("PASSED", "FAILED", "INCONCLUSIVE")) {
            if (output.contains("\n" + verdict + ": ")) {
                return verdict;
            }
        }
        throw new AssertionError("the page shows no verdict for '" + command + "':\n" + output);
    }

    /** The commands of a session (lines starting with "$ ") and the lines after each. */
    private static List<Step> steps(String session) {
        List<Step> steps = new ArrayList<>();
        String command = null;
        StringBuilder output = new StringBuilder();
        for (String line : session.split("\n")) {
            if (line.startsWith("$ ")) {
                if (command != null) {
                    steps.add(new Step(command, output.toString()));
                }
                command = line.substring(2);
                output.setLength(0);
            } else {
                output.append(line).append('\n');
            }
        }
        if (command != null) {
            steps.add(new Step(command, output.toString()));
        }
        return steps;
    }

    /** The text with runs of blanks made one, without the colour codes Debian's mvn prints even in batch mode. */
    private static String oneLine(String text) {
        return text.replaceAll("\u001B\\[[0-9;]*m", "").trim().replaceAll("\\s+", " ");
    }
}
