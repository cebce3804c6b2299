package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.dtron.api.ChildJvm;
import io.dtron.cli.DtronCommand;
import io.dtron.models.ticker.TickerBusAdapter;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.ListeningSockets;
import io.dtron.testsupport.ListeningSockets.Listener;
import java.net.InetAddress;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Map;
import java.util.Set;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.stream.Collectors;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/**
 * Every socket a DTRON process listens on, read from {@code /proc} again and again while it runs, is on the bind
 * address (loopback by default, {@code --bind}'s otherwise) and on a port of {@code --port .. --port+--port-range}:
 * the README's quick start (the tester and the ticker's bus adapter in one JVM) and a distributed run of two testers
 * in two JVMs, as distributed.md runs them. None listens on every interface, none on UDP.
 */
@Timeout(value = 240, unit = TimeUnit.SECONDS)
class ListeningSocketsTest {
    private static final Path MODELS = Path.of("src/main/resources/io/dtron/models");
    private static final Duration RUN = Duration.ofSeconds(150);
    private static final int RANGE = 5;

    @TempDir
    Path dir;

    @BeforeAll
    static void linux() {
        assumeTrue(ListeningSockets.available(), "needs Linux's /proc");
    }

    /** {@code ADDRESS:PORT} of each TCP listener; fails on a UDP one. */
    private static Set<String> tcp(Set<Listener> listeners) {
        assertTrue(listeners.stream().allMatch(l -> l.protocol().equals("tcp")), "no UDP socket: " + listeners);
        return listeners.stream().map(l -> l.address().getHostAddress() + ":" + l.port()).collect(Collectors.toSet());
    }

    private static void assertAllAt(String bind, int port, Set<Listener> listeners) {
        for (Listener l : listeners) {
            assertEquals(bind, l.address().getHostAddress(), "bound to the bind address: " + listeners);
            assertTrue(l.port() >= port && l.port() <= port + RANGE, "within --port and --port-range: " + listeners);
        }
    }

    @ParameterizedTest
    @ValueSource(strings = {"", "127.0.0.2"})
    void theQuickStartListensOnlyAtTheBindAddress(String bind) throws Exception {
        String address = bind.isEmpty() ? "127.0.0.1" : bind;
        int port = FreePorts.range(RANGE, InetAddress.getByName(address));
        String[] args = {"run", MODELS.resolve("ticker.xml").toString(), "--adapter", TickerBusAdapter.class.getName(),
                "--timeunit", "10000", "--timeout", "300", "--delay-policy", "eager", "--cluster", cluster(),
                "--port", Integer.toString(port), "--port-range", Integer.toString(RANGE)};
        if (!bind.isEmpty()) {
            args = append(args, "--bind", bind);
        }
        try (ChildJvm run = ChildJvm.start(DtronCommand.class, dir.resolve("quickstart.log"), args)) {
            Set<Listener> listeners = ListeningSockets.whileRunning(RUN, run.toHandle()).get(run.toHandle().pid());
            run.waitFor(RUN);
            // the verdict is the quick start's own business (at 10 ms per time unit, a busy host may decide it)
            assertTrue(run.output().contains("dtron run: every channel is served")
                    && run.output().contains("\nstatistics: "), "the run ran to its end: " + run.output());
            // the tester and the adapter: bus ports port, port + 1
            assertEquals(2, tcp(listeners).size(), listeners::toString);
            assertAllAt(address, port, listeners);
        }
    }

    @ParameterizedTest
    @ValueSource(strings = {"127.0.0.1,127.0.0.2", "127.0.0.2,127.0.0.3"})
    void aDistributedRunListensOnlyAtEachTestersBindAddress(String binds) throws Exception {
        String[] at = binds.split(",");
        int port = FreePorts.range(RANGE, InetAddress.getByName(at[0]), InetAddress.getByName(at[1]));
        String cluster = cluster();
        try (ChildJvm mover = tester("mover", "conversation/mover.xta", cluster, at[0], binds, port, "--testers",
                "2");
                ChildJvm responder = tester("responder", "conversation/responder.xta", cluster, at[1], binds, port,
                        "--join")) {
            Map<Long, Set<Listener>> seen = ListeningSockets.whileRunning(RUN, mover.toHandle(), responder.toHandle());
            Set<Listener> moverListeners = seen.get(mover.toHandle().pid());
            Set<Listener> responderListeners = seen.get(responder.toHandle().pid());
            mover.waitFor(RUN);
            responder.waitFor(RUN);
            assertTrue(mover.output().contains("\nstatistics: ") && responder.output().contains("\nstatistics: "),
                    "both ran to their verdicts: " + mover.output() + responder.output());
            assertEquals(1, tcp(moverListeners).size(), "a bus port: " + moverListeners);
            assertEquals(1, tcp(responderListeners).size(), "a bus port: " + responderListeners);
            assertAllAt(at[0], port, moverListeners);
            assertAllAt(at[1], port, responderListeners);
        }
    }

    private ChildJvm tester(String name, String model, String cluster, String bind, String members, int port,
            String... more) throws Exception {
        String[] args = {"run", MODELS.resolve(model).toString(), "--cluster", cluster, "--bind", bind, "--members",
            members, "--port", Integer.toString(port), "--port-range", Integer.toString(RANGE), "--timeunit", "20000",
            "--timeout", "150", "--delay-policy", "eager", "--seed", "7", "--wait-timeout", "90"};
        return ChildJvm.start(DtronCommand.class, dir.resolve(name + ".log"), append(args, more));
    }

    private static String cluster() {
        return "sockets-" + UUID.randomUUID().toString().substring(0, 8);
    }

    private static String[] append(String[] args, String... more) {
        String[] all = java.util.Arrays.copyOf(args, args.length + more.length);
        System.arraycopy(more, 0, all, args.length, more.length);
        return all;
    }
}
