package io.dtron.models.web;

import static org.awaitility.Awaitility.await;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.PageProjects;
import java.io.IOException;
import java.net.HttpURLConnection;
import java.net.ServerSocket;
import java.net.URI;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code web-testing.md} from an empty folder, as the page says: its page served by the page's Python command, its
 * {@code pom.xml}, model, adapter and properties as they are, and its run command (step 5) run by the {@code mvn} on
 * the {@code PATH} against the artifacts this build installed (and Maven Central for the rest), with headless
 * Chromium. Changed from the page, because tests run beside each other: the web server's port (a free one, given to
 * the adapters by the system properties the page says override the properties file) and the bus name. The run must
 * end as the page says a correct page may: PASSED, or INCONCLUSIVE with an input executed too late.
 */
@Timeout(value = 420, unit = TimeUnit.SECONDS)
class WebTestingPageTest {
    private static final Pattern SERVER = Pattern.compile("`(cd site && python3 -m http\\.server) (\\d+)"
            + " (--bind 127\\.0\\.0\\.1)`");
    private static final Pattern TOO_LATE = Pattern.compile("\nINCONCLUSIVE: input \\w+\\([^)]*\\) was executed at"
            + " t=[0-9.]+, when the environment no longer allowed it, .*\\(input executed too late\\)");

    @TempDir
    Path dir;

    @Test
    void theGreeterOfThePagePassesBuiltAndRunAsThePageSays() throws Exception {
        Path repository = PageProjects.requireInstalled("selenium-adapter");
        PageProjects.requireInstalled("dtron-cli");
        DocPage page = DocPage.read("web-testing.md");

        Path site = Files.createDirectories(dir.resolve("site"));
        List<String> html = page.blocks("html");
        assertEquals(1, html.size(), page + " shows one page, site/index.html");
        Files.writeString(site.resolve("index.html"), html.get(0));
        Path project = Files.createDirectories(dir.resolve("greeter"));
        Files.writeString(project.resolve("pom.xml"), page.block("xml", "<project"));
        Files.writeString(project.resolve("greeter.xml"), page.block("xml", "<nta>"));
        Path sources = Files.createDirectories(project.resolve("src/main/java/com/example/web"));
        Files.writeString(sources.resolve("Greet.java"), page.javaClass("Greet"));
        Path resources = Files.createDirectories(project.resolve("src/main/resources/com/example/web"));
        Files.writeString(resources.resolve("adapters.properties"),
                page.blockAfter("The locators and the address live in").code());

        Matcher server = SERVER.matcher(page.text());
        assertTrue(server.find(), page + " serves the page with `cd site && python3 -m http.server PORT --bind 127.0.0.1`");
        int port = freePort();
        String base = "http://127.0.0.1:" + port;
        assertTrue(Files.readString(resources.resolve("adapters.properties")).contains("BASE_URL=http://127.0.0.1:"
                + server.group(2)), "the properties point at the page's server");
        Process python = new ProcessBuilder("bash", "-c", server.group(1) + " " + port + " " + server.group(3))
                .directory(dir.toFile()).redirectErrorStream(true).redirectOutput(dir.resolve("http.log").toFile())
                .start();
        try {
            await().atMost(Duration.ofSeconds(60)).ignoreExceptions().until(() -> served(base + "/index.html"));
            List<String> command = runCommand(page);
            command.addAll(1, List.of("-B", "-Dmaven.repo.local=" + repository, "-DBASE_URL=" + base,
                    "-Ddtron.startPage=" + base + "/index.html"));
            String bus = " --cluster web-" + UUID.randomUUID().toString().substring(0, 8);
            command.replaceAll(w -> w.startsWith("-Dexec.args=") ? w + bus : w);
            command.set(0, PageProjects.mvn());
            Path log = dir.resolve("mvn.log");
            ProcessBuilder builder = new ProcessBuilder(command).directory(project.toFile()).redirectErrorStream(true)
                    .redirectOutput(log.toFile());
            builder.environment().remove("MAVEN_PROJECTBASEDIR");
            builder.environment().remove("MAVEN_CMD_LINE_ARGS");
            Process mvn = builder.start();
            try {
                if (!mvn.waitFor(360, TimeUnit.SECONDS)) {
                    fail(command + " still runs after 360 s:\n" + Files.readString(log));
                }
            } finally {
                stop(mvn);
            }
            String out = Files.readString(log);
            String context = command + " printed:\n" + out;
            out.lines().filter(l -> l.matches("(PASSED|FAILED|INCONCLUSIVE): .*"))
                    .forEach(l -> System.out.println("WebTestingPageTest: " + l));
            if (mvn.exitValue() == 3) {
                assertTrue(TOO_LATE.matcher(out).find(), context);
            } else {
                assertEquals(0, mvn.exitValue(), context);
                assertTrue(out.contains("\nPASSED: the timeout of 100 time units was reached after "), context);
            }
        } finally {
            stop(python);
        }
    }

    /**
     * The page's command of step 5: the first line of the block after the step's heading and the lines it continues
     * onto (ending with a backslash), split into words as the shell does (double quotes keep a word together).
     */
    private static List<String> runCommand(DocPage page) {
        StringBuilder line = new StringBuilder();
        for (String l : page.blockAfter("## 5. The run").code().split("\n")) {
            line.append(l);
            if (!l.endsWith("\\")) {
                break;
            }
            line.setLength(line.length() - 1);
        }
        String text = line.toString();
        assertTrue(text.startsWith("$ mvn "), "step 5 runs mvn: " + text);
        List<String> words = new ArrayList<>();
        StringBuilder word = new StringBuilder();
        boolean quoted = false;
        boolean any = false;
        for (char c : text.substring(2).toCharArray()) {
            if (c == '"') {
                quoted = !quoted;
                any = true;
            } else if (Character.isWhitespace(c) && !quoted) {
                if (any) {
                    words.add(word.toString());
                }
                word.setLength(0);
                any = false;
            } else {
                word.append(c);
                any = true;
            }
        }
        if (any) {
            words.add(word.toString());
        }
        return words;
    }

    private static boolean served(String url) throws IOException {
        HttpURLConnection connection = (HttpURLConnection) URI.create(url).toURL().openConnection();
        try {
            return connection.getResponseCode() == 200;
        } finally {
            connection.disconnect();
        }
    }

    private static int freePort() throws IOException {
        try (ServerSocket socket = new ServerSocket(0, 1, java.net.InetAddress.getLoopbackAddress())) {
            return socket.getLocalPort();
        }
    }

    private static void stop(Process process) {
        process.descendants().forEach(ProcessHandle::destroyForcibly);
        process.destroyForcibly();
    }
}
