package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import java.nio.file.Files;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The Python and C pages show the tickers the NATS tests run: the page's code block is the example file, so that
 * what a reader copies is what passed.
 */
class NatsPagesTest {
    /** The fenced blocks of a page opened with {@code ```info}. */
    private static List<String> blocks(String page, String info) throws Exception {
        return DocPage.read(page).blocks(info);
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
