package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.dtron.api.ChildJvm;
import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.ListeningSockets;
import io.dtron.testsupport.ListeningSockets.Listener;
import java.net.InetAddress;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import org.awaitility.Awaitility;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/**
 * The sockets {@code dtron tron} listens on, read from {@code /proc} again and again while it runs with a TRON
 * adapter: TRON's virtual clock server ({@code -Q PORT}) and the port it waits for the adapter on ({@code -- PORT})
 * are on the bind address (127.0.0.1 by default, {@code --bind}'s otherwise), and nothing else listens.
 */
@Timeout(value = 180, unit = TimeUnit.SECONDS)
class TronListeningSocketsTest {
    private static final Duration RUN = Duration.ofSeconds(120);
    private static Path lightContr;

    @TempDir
    Path dir;

    @BeforeAll
    static void find() {
        assumeTrue(ListeningSockets.available(), "needs Linux's /proc");
        lightContr = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron", "LightContr.xml");
    }

    private static List<String> tron(String bind, String... args) {
        List<String> all = new ArrayList<>(List.of("tron"));
        if (!bind.isEmpty()) {
            all.addAll(List.of("--bind", bind));
        }
        all.addAll(List.of(args));
        return all;
    }

    @ParameterizedTest
    @ValueSource(strings = {"", "127.0.0.2"})
    void theVirtualClockServerListensOnlyAtTheBindAddress(String bind) throws Exception {
        String address = bind.isEmpty() ? "127.0.0.1" : bind;
        int clock = FreePorts.port(InetAddress.getByName(address));
        int lampPort = FreePorts.port();
        List<String> args = tron(bind, "-Q", Integer.toString(clock), "-X", "8", lightContr.toString(), "--",
                "127.0.0.1", Integer.toString(lampPort));
        Listener clockServer = new Listener("tcp", InetAddress.getByName(address), clock);
        try (ChildJvm tron = ChildJvm.start(DtronCommand.class, dir.resolve("tron.log"),
                args.toArray(String[]::new))) {
            // as TRON's samples run: the clock server first, then the lamp, whose threads connect to it
            Set<Listener> listeners = awaitListener(tron, clockServer);
            try (ChildJvm lamp = ChildJvm.start(TronSampleLamp.class, dir.resolve("lamp.log"), "-C", address,
                    Integer.toString(clock), Integer.toString(lampPort), "correct", "5000", "1000")) {
                listeners.addAll(ListeningSockets.whileRunning(RUN, tron.toHandle()).get(tron.toHandle().pid()));
                assertEquals(0, tron.waitFor(RUN), tron.output() + lamp.output());
            }
            assertTrue(tron.output().contains("TEST PASSED"), tron.output());
            assertEquals(Set.of(clockServer), listeners);
        }
    }

    /** Returns the process's listening sockets, once {@code expected} is among them (or the process ended). */
    private static Set<Listener> awaitListener(ChildJvm process, Listener expected) {
        Set<Listener> listeners = new HashSet<>();
        Awaitility.await().atMost(RUN).pollInterval(Duration.ofMillis(50)).until(() -> {
            listeners.addAll(ListeningSockets.of(process.toHandle().pid()));
            return listeners.contains(expected) || !process.toHandle().isAlive();
        });
        return listeners;
    }

    @ParameterizedTest
    @ValueSource(strings = {"", "127.0.0.2"})
    void waitingForTheAdapterListensOnlyAtTheBindAddress(String bind) throws Exception {
        String address = bind.isEmpty() ? "127.0.0.1" : bind;
        int port = FreePorts.port(InetAddress.getByName(address));
        List<String> args = tron(bind, "--virtual-time", "-X", "9", "-F", "3000", lightContr.toString(), "--",
                Integer.toString(port));
        Listener waiting = new Listener("tcp", InetAddress.getByName(address), port);
        try (ChildJvm tron = ChildJvm.start(DtronCommand.class, dir.resolve("tron.log"),
                args.toArray(String[]::new))) {
            Set<Listener> listeners = awaitListener(tron, waiting);
            CompletableFuture<Void> lamp = CompletableFuture.runAsync(() -> {
                try (TronAdapterClient client = TronAdapterClient.connect(address, port,
                        TronAdapterClient.TimeMode.SHARED_VIRTUAL_CLOCK)) {
                    TronLamp.attach(client, 1000, false, 1000);
                    client.awaitEnd(Duration.ofSeconds(60));
                } catch (Exception e) {
                    throw new IllegalStateException(e);
                }
            });
            listeners.addAll(ListeningSockets.whileRunning(RUN, tron.toHandle()).get(tron.toHandle().pid()));
            assertEquals(0, tron.waitFor(RUN), tron.output());
            lamp.get(60, TimeUnit.SECONDS);
            assertTrue(tron.output().contains("TEST PASSED"), tron.output());
            assertEquals(Set.of(waiting), listeners);
        }
    }
}
