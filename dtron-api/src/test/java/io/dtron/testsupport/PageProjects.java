package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import java.io.File;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

/**
 * What the tests that build the pages' Maven projects share: the {@code mvn} a user runs, the build's local
 * repository and version, which the build passes as system properties ({@code dtron.localRepository},
 * {@code dtron.version}), and the check that the repository holds the artifact this build made.
 */
public final class PageProjects {
    /** How long a page's Maven build may take (it may download plugins from Maven Central). */
    public static final Duration BUILD = Duration.ofSeconds(180);

    private PageProjects() {
    }

    /**
     * The {@code mvn} executable a user would run: the first on the {@code PATH} (Debian's Maven 3.8.7 here), not the
     * one running the build, so that a page's project is built as the page says.
     */
    public static String mvn() {
        String name = System.getProperty("os.name").startsWith("Windows") ? "mvn.cmd" : "mvn";
        for (String entry : System.getenv().getOrDefault("PATH", "").split(File.pathSeparator)) {
            if (!entry.isEmpty() && Files.isExecutable(Path.of(entry, name))) {
                return Path.of(entry, name).toString();
            }
        }
        throw new AssertionError("no " + name + " on the PATH: the pages' projects are built with the mvn a user runs");
    }

    /** This build's version. */
    public static String version() {
        return property("dtron.version");
    }

    /**
     * Returns the build's local repository after checking that it holds the jar of module {@code artifactId} this
     * build made; fails clearly unless it does.
     */
    public static Path requireInstalled(String artifactId) throws Exception {
        String version = version();
        Path repository = Path.of(property("dtron.localRepository"));
        String name = artifactId + "-" + version + ".jar";
        Path installed = repository.resolve(Path.of("io", "dtron", artifactId, version, name));
        Path built = Path.of("..", artifactId, "target", name).toAbsolutePath().normalize();
        assertTrue(Files.isRegularFile(built), "this build made no " + built);
        if (!Files.isRegularFile(installed) || Files.mismatch(installed, built) != -1) {
            fail("the local repository " + repository + " holds " + (Files.isRegularFile(installed)
                    ? "another " + artifactId + " " + version + " than this build made (" + built + ")"
                    : "no " + artifactId + " " + version) + ": run mvn install (the README's test command), not mvn"
                    + " verify, so that the build installs " + artifactId + " before this test builds a project"
                    + " depending on it");
        }
        return repository;
    }

    private static String property(String name) {
        String value = System.getProperty(name, "");
        if (value.isEmpty()) {
            fail("system property " + name + " is not set: run the test through Maven (the module's pom sets it)");
        }
        return value;
    }
}
