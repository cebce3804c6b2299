package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assertions.fail;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;

/**
 * What the tests that build the pages' Maven projects share: the build's local repository and version, which the
 * build passes as system properties ({@code dtron.localRepository}, {@code dtron.version}), and the check that the
 * repository holds the artifact this build made.
 */
final class PageProjects {
    /** How long a page's Maven build may take (it may download plugins from Maven Central). */
    static final Duration BUILD = Duration.ofSeconds(180);

    private PageProjects() {
    }

    /** This build's version. */
    static String version() {
        return property("dtron.version");
    }

    /**
     * Returns the build's local repository after checking that it holds the jar of module {@code artifactId} this
     * build made; fails clearly unless it does.
     */
    static Path requireInstalled(String artifactId) throws Exception {
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
            fail("system property " + name + " is not set: run the test through Maven (failsafe in dtron-cli's pom)");
        }
        return value;
    }
}
