package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.ShellSession;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The bundled samples' commands of {@code in-process.md} run as they are, by {@code bash} in the project's folder
 * (where their paths point), after the build made {@code dtron.jar} and the models' classes: the ticker in virtual
 * time passes, its {@code slow} variant fails, as the page says.
 */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class BundledSamplesPageTest {
    private static final Path ROOT = Path.of("..").toAbsolutePath().normalize();
    private static final Pattern EXIT = Pattern.compile("(?m)^exit (\\d+)$");

    @TempDir
    Path dir;

    @Test
    void theTickerPassesAndItsSlowVariantFailsInVirtualTime() throws Exception {
        assertTrue(Files.isRegularFile(ROOT.resolve("dtron-cli/target/dtron.jar")),
                "the page runs dtron-cli/target/dtron.jar: build it first (mvn install)");
        String block = DocPage.read("in-process.md").blockAfter("## The bundled samples").code();
        List<String> script = new ArrayList<>();
        List<String> suts = new ArrayList<>();
        for (String command : block.split("\n")) {
            assertTrue(command.startsWith("java -jar dtron-cli/target/dtron.jar run "), command);
            suts.add(command.substring(command.indexOf("--sut ") + 6).split(" ")[0]);
            script.add(command);
            script.add("echo exit $?");
        }
        assertEquals(List.of("io.dtron.models.ticker.TickerSystem", "io.dtron.models.ticker.TickerSystem:slow"), suts);
        String output = ShellSession.run(ROOT, script, dir.resolve("samples.log"), Duration.ofSeconds(100));
        List<String> exits = new ArrayList<>();
        Matcher exit = EXIT.matcher(output);
        while (exit.find()) {
            exits.add(exit.group(1));
        }
        assertEquals(List.of("0", "2"), exits, "PASSED, then FAILED: " + output);
        assertTrue(output.contains("\nPASSED: ") && output.contains("\nFAILED: "), output);
    }
}
