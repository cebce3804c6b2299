package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.FreePorts;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/** A port in use, or port options that cannot work, are one line naming the ports and the option, with exit 1. */
@Timeout(value = 120, unit = TimeUnit.SECONDS)
class PortsInUseTest {
    private static final InetAddress LOOPBACK = InetAddress.getLoopbackAddress();

    @TempDir
    static Path dir;
    private static Path model;
    private static Path lightContr;
    private final List<ServerSocket> held = new ArrayList<>();

    @BeforeAll
    static void models() throws IOException {
        model = dir.resolve("ticker.xta");
        Files.writeString(model, """
                chan i_reset, o_tick;
                process Ticker() { clock x; state Running { x <= 12 }; init Running;
                    trans Running -> Running { guard x >= 8; sync o_tick!; assign x = 0; },
                          Running -> Running { sync i_reset?; assign x = 0; }; }
                process Env() { state Watching; init Watching;
                    trans Watching -> Watching { sync i_reset!; }, Watching -> Watching { sync o_tick?; }; }
                system Ticker, Env;
                """);
        lightContr = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron", "LightContr.xml");
    }

    @AfterEach
    void release() throws IOException {
        for (ServerSocket socket : held) {
            socket.close();
        }
    }

    /** Holds the ports at loopback, as another process would, and returns the first. */
    private int hold(int first, int count) throws IOException {
        for (int port = first; port < first + count; port++) {
            held.add(new ServerSocket(port, 1, LOOPBACK));
        }
        return first;
    }

    private static String oneLine(CommandRun r) {
        assertEquals(1, r.exit(), r.out() + r.err());
        assertFalse(r.err().contains("\tat ") || r.err().contains("Exception"), "no stack trace: " + r.err());
        List<String> lines = r.err().lines().toList();
        assertEquals(1, lines.size(), r.err());
        return lines.get(0);
    }

    @Test
    void busPortsInUseNameThePortsAndTheOptions() throws Exception {
        int port = hold(FreePorts.range(3), 4);
        String error = oneLine(CommandRun.of("run", model.toString(), "--port", Integer.toString(port),
                "--port-range", "3", "--wait-timeout", "1"));
        assertEquals("dtron run: cannot join bus 'dtron': no free port for the bus on 127.0.0.1 in " + port + ".."
                + (port + 3) + " (port " + port + ", port range 3): a member needs one, and ports " + port + "-"
                + (port + 3) + " are in use; choose free ones with the port and port range options (dtron: --port,"
                + " --port-range)",
                error);
    }

    @Test
    void theErrorCliMdShowsIsWhatDtronPrintsWhenEveryPortIsInUse() throws Exception {
        String shown = DocPage.read("cli.md").blockAfter("naming the ports in use and the options (exit 1):").code()
                .strip();
        int port = hold(FreePorts.range(61), 62); // the page's 7800..7861, moved to free ports
        String error = oneLine(CommandRun.of("run", model.toString(), "--port", Integer.toString(port),
                "--wait-timeout", "1"));
        assertEquals(shown.replace("7861", Integer.toString(port + 61)).replace("7800", Integer.toString(port)),
                error);
    }

    @Test
    void portOptionsThatCannotWorkAreUsageErrors() {
        CommandRun zero = CommandRun.of("run", model.toString(), "--port-range", "0");
        assertEquals(1, zero.exit(), zero.err());
        assertTrue(zero.err().startsWith("dtron run: --port must be 1 to 65535 and --port-range 1 to 65535"
                + " (the bus ports"), zero.err());
        CommandRun beyond = CommandRun.of("run", model.toString(), "--port", "65500");
        assertEquals(1, beyond.exit(), beyond.err());
        assertTrue(beyond.err().startsWith("dtron run: --port 65500 --port-range 61: the ports 65500..65561 go"
                + " beyond 65535"), beyond.err());
    }

    @Test
    void aTronAdapterPortInUseNamesTheAddressAndPort() throws Exception {
        int port = hold(FreePorts.port(), 1);
        String run = oneLine(CommandRun.of("run", lightContr.toString(), "--tron-adapter", Integer.toString(port)));
        assertTrue(run.startsWith("dtron run: --tron-adapter " + port + ": cannot listen for the adapter on 127.0.0.1:"
                + port + ": "), run);
        CommandRun tron = CommandRun.of("tron", lightContr.toString(), "--", Integer.toString(port));
        String listen = oneLine(tron);
        assertTrue(listen.startsWith("dtron tron: -- " + port + ": cannot listen for the adapter on 127.0.0.1:"
                + port + ": "), listen);
        String clock = oneLine(CommandRun.of("tron", "-Q", Integer.toString(port), lightContr.toString(), "--",
                "127.0.0.1", Integer.toString(port)));
        assertTrue(clock.startsWith("dtron tron: -Q " + port + ": cannot serve the virtual clock on 127.0.0.1:"
                + port + ": "), clock);
    }
}
