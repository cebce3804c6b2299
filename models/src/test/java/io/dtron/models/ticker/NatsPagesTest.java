package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The Python and C pages show the tickers the NATS tests run: the page's code block is the example file, so that
 * what a reader copies is what passed.
 */
class NatsPagesTest {
    private static final Path SITE = Path.of("../src/site/markdown");

    /** The fenced blocks of a page opened with {@code ```info}. */
    private static List<String> blocks(String page, String info) throws Exception {
        List<String> found = new ArrayList<>();
        StringBuilder code = null;
        for (String line : Files.readAllLines(SITE.resolve(page))) {
            if (code == null && line.equals("```" + info)) {
                code = new StringBuilder();
            } else if (code != null && line.equals("```")) {
                found.add(code.toString());
                code = null;
            } else if (code != null) {
                code.append(line).append('\n');
            }
        }
        return found;
    }

    @Test
    void thePythonPageShowsThePythonTicker() throws Exception {
        List<String> python = blocks("python.md", "python");
        assertEquals(1, python.size());
        assertEquals(Files.readString(NatsClients.PYTHON.resolve("examples/ticker.py")), python.get(0));
    }

    @Test
    void theCPageShowsTheCTickerAndBuildsItAgainstTheClient() throws Exception {
        List<String> c = blocks("c.md", "c");
        assertEquals(1, c.size());
        assertEquals(Files.readString(NatsClients.C.resolve("examples/ticker.c")), c.get(0));
        List<String> cmake = blocks("c.md", "cmake");
        assertEquals(1, cmake.size());
        assertTrue(cmake.get(0).contains("add_subdirectory($ENV{HOME}/dtron/clients/c dtron)")
                && cmake.get(0).contains("target_link_libraries(ticker dtron)"), cmake.get(0));
    }
}
