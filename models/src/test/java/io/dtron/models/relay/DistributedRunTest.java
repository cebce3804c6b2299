package io.dtron.models.relay;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.cli.DtronCommand;
import io.dtron.testsupport.BusSummary;
import io.dtron.testsupport.FreePorts;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Runs of several testers, each a JVM of its own with its own model, on one bus across loopback addresses: the
 * relay's two ports judged by two testers (127.0.0.1 and 127.0.0.2) with its adapters on a third address
 * (127.0.0.3), and the conversation of two models that test each other.
 */
@Timeout(value = 240, unit = TimeUnit.SECONDS)
class DistributedRunTest {
    private static final Path MODELS = Path.of("src/main/resources/io/dtron/models");
    private static final String MEMBERS = "127.0.0.1,127.0.0.2,127.0.0.3";
    private static final Duration WAIT = Duration.ofSeconds(120);
    /**
     * 100 ms per time unit: the models' narrowest windows (7 units) are then wider than what a busy machine
     * adds to three JVMs' timing (a relay 26 ms late, a tester held up 200 ms were seen at 20 ms per unit).
     */
    private static final long UNIT_MICROS = 100_000;

    private static String cluster() {
        return "distributed-" + UUID.randomUUID().toString().substring(0, 8);
    }

    /** The bus's port range in these runs: 3 bus ports per address (2 testers, or 2 adapters, and one spare). */
    static final int RANGE = 5;

    /** Instead of a port: the bus's default ports, as distributed.md's commands have them. */
    private static final int DEFAULT_PORTS = -1;

    /** The first port of a range free at the three addresses. */
    static int freePort() throws Exception {
        return FreePorts.range(RANGE, InetAddress.getByName("127.0.0.1"), InetAddress.getByName("127.0.0.2"),
                InetAddress.getByName("127.0.0.3"));
    }

    static ChildJvm tester(Path dir, String name, String model, String cluster, String address, int port,
            String... more) throws Exception {
        return tester(dir, name, model, cluster, address, port, UNIT_MICROS, more);
    }

    private static ChildJvm tester(Path dir, String name, String model, String cluster, String address, int port,
            long timeUnit, String... more) throws Exception {
        List<String> args = new ArrayList<>(List.of("run", MODELS.resolve(model).toString(), "--cluster", cluster,
                "--bind", address, "--members", MEMBERS, "--timeunit", Long.toString(timeUnit), "--timeout", "60",
                "--delay-policy",
                "eager", "--seed", "7", "--wait-timeout", "90"));
        if (port != DEFAULT_PORTS) {
            args.addAll(List.of("--port", Integer.toString(port), "--port-range", Integer.toString(RANGE)));
        }
        args.addAll(List.of(more));
        return ChildJvm.start(DtronCommand.class, dir.resolve(name + ".log"), args.toArray(String[]::new));
    }

    /** The exit codes and outputs of the relay's two testers, with the relay's output. */
    record Relay(int port1, int port2, String port1Output, String port2Output, String relayOutput) {
        String all() {
            return port1Output + port2Output + relayOutput;
        }
    }

    /** Runs both ports' testers against a relay of the variant, each port in a JVM of its own. */
    static Relay relay(Path dir, String variant) throws Exception {
        return relay(dir, variant, freePort(), UNIT_MICROS);
    }

    /** Runs the relay as {@link #relay(Path, String)} does, on the port range from {@code port}, in the time unit. */
    private static Relay relay(Path dir, String variant, int port, long timeUnit) throws Exception {
        String cluster = cluster();
        String[] relayArgs = port == DEFAULT_PORTS ? new String[] {cluster, "127.0.0.3", MEMBERS, variant}
                : new String[] {cluster, "127.0.0.3", MEMBERS, variant, Integer.toString(port),
                    Integer.toString(RANGE)};
        try (ChildJvm port1 = tester(dir, "port1", "relay/port1.xta", cluster, "127.0.0.1", port, timeUnit,
                "--testers", "2", "--trace", dir.resolve("port1.jsonl").toString());
                ChildJvm port2 = tester(dir, "port2", "relay/port2.xta", cluster, "127.0.0.2", port, timeUnit,
                        "--join", "--trace", dir.resolve("port2.jsonl").toString());
                ChildJvm relay = ChildJvm.start(RelayAdapters.class, dir.resolve("relay.log"), relayArgs)) {
            int second = port2.waitFor(WAIT);
            int first = port1.waitFor(WAIT);
            return new Relay(first, second, port1.output(), port2.output(), relay.output());
        }
    }

    @Test
    void bothPortsOfACorrectRelayPass(@TempDir Path dir) throws Exception {
        Relay r = relay(dir, "correct");
        assertEquals(0, r.port1(), r.all());
        assertEquals(0, r.port2(), r.all());
        assertTrue(r.port1Output().contains("PASSED: the timeout of 60 time units was reached"), r.all());
        assertTrue(r.port2Output().contains("PASSED: the timeout of 60 time units was reached"), r.all());
        assertTrue(r.port1Output().contains("dtron run: the run's testers: "), r.all());
        assertTrue(r.port1Output().matches("(?s).*tester \\S+ of this run: PASSED.*"), r.all());
        // the first tester's model has no resp: it neither rejects nor warns about the second's channel...
        assertFalse(r.port1Output().contains("Rejected a message"), r.all());
        BusSummary.assertNothingOfTheRunRejected(r.port1Output());
        // ...and its trace is global: the second tester's responses are in it, as in the second's own trace
        List<String> port1 = busMessages(dir.resolve("port1.jsonl"));
        List<String> port2 = busMessages(dir.resolve("port2.jsonl"));
        List<String> responses = port1.stream().filter(m -> m.startsWith("resp/")).toList();
        assertFalse(responses.isEmpty(), "the relay's responses are in the first tester's trace: " + port1);
        assertTrue(port2.containsAll(responses), "the second tester traced them too: " + port2);
        assertSameOrder(port1, port2);
    }

    /**
     * distributed.md's commands, on the default ports, while members of another bus hold the first of them at each
     * of the three addresses: every member takes the next free ports, on its own address only. At the other tests'
     * 100 ms per unit (the page has 1 s), so that a busy host does not decide the verdict this test is not about.
     */
    @Test
    void theRelayPassesOnTheDefaultPortsWhileAnotherBusHoldsTheFirstOfThem(@TempDir Path dir) throws Exception {
        List<Dtron> otherBus = new ArrayList<>();
        String other = "other-" + cluster();
        try {
            for (String address : MEMBERS.split(",")) {
                for (int i = 0; i < 2; i++) {
                    otherBus.add(Dtron.connect(DtronOptions.builder().clusterName(other)
                            .bindAddress(InetAddress.getByName(address)).build()));
                }
            }
            Relay r = relay(dir, "correct", DEFAULT_PORTS, UNIT_MICROS);
            assertEquals(0, r.port1(), r.all());
            assertEquals(0, r.port2(), r.all());
            assertTrue(r.port2Output().contains("PASSED: the timeout of 60 time units was reached"), r.all());
        } finally {
            otherBus.forEach(Dtron::close);
        }
    }

    @Test
    void theRelaySaysInOneLineWhichPortsAreInUse(@TempDir Path dir) throws Exception {
        InetAddress address = InetAddress.getByName("127.0.0.3");
        int port = FreePorts.range(1, address);
        try (ServerSocket bus = new ServerSocket(port, 1, address);
                ServerSocket otherBus = new ServerSocket(port + 1, 1, address);
                ChildJvm relay = ChildJvm.start(RelayAdapters.class, dir.resolve("relay.log"), cluster(),
                        "127.0.0.3", "127.0.0.3", "correct", Integer.toString(port), "1")) {
            assertEquals(1, relay.waitFor(WAIT), relay.output());
            String output = relay.output();
            String error = output.lines().filter(l -> l.startsWith("RelayAdapters: ")).findFirst()
                    .orElseThrow(() -> new AssertionError(output));
            assertTrue(error.contains(": no free port for the bus on 127.0.0.3 in " + port + ".." + (port + 1)),
                    error);
            assertTrue(error.contains("ports " + port + "-" + (port + 1) + " are in use"), error);
            assertTrue(error.endsWith("(dtron: --port, --port-range)"), error);
            assertFalse(relay.output().contains("\tat ") || relay.output().contains("Exception"), relay.output());
        }
    }

    @Test
    void aLateResponseFailsAtPortTwoAndEndsPortOneWithTheReason(@TempDir Path dir) throws Exception {
        Relay r = relay(dir, "late");
        assertEquals(2, r.port2(), r.all());
        // the late response, or the next request if it comes first, is seen after the response's deadline, or
        // nothing by it (after how the request was taken)
        assertTrue(r.port2Output().matches("(?s).*FAILED: (?:[^\n]*?; then )?(?:output (?:resp|req)\\(\\) observed at"
                + "|no output came by).*"),
                r.all());
        assertTrue(r.port2Output().contains("resp between"), "the response was due: " + r.all());
        assertEquals(3, r.port1(), r.all());
        assertTrue(r.port1Output().matches("(?s).*INCONCLUSIVE: tester \\S+ of this run ended it FAILED.*"), r.all());
    }

    @Test
    void twoModelsInAConversationBothPassAndTraceTheSameBus(@TempDir Path dir) throws Exception {
        String cluster = cluster();
        Path moverTrace = dir.resolve("mover.jsonl");
        Path responderTrace = dir.resolve("responder.jsonl");
        int port = freePort();
        try (ChildJvm mover = tester(dir, "mover", "conversation/mover.xta", cluster, "127.0.0.1", port, "--testers",
                "2", "--trace", moverTrace.toString());
                ChildJvm responder = tester(dir, "responder", "conversation/responder.xta", cluster, "127.0.0.2",
                        port, "--join", "--trace", responderTrace.toString())) {
            int first = mover.waitFor(WAIT);
            int second = responder.waitFor(WAIT);
            assertEquals(0, first, mover.output() + responder.output());
            assertEquals(0, second, responder.output() + mover.output());
            assertTrue(mover.output().contains("PASSED"), mover.output());
            assertTrue(responder.output().contains("PASSED"), responder.output());
        }
        List<String> shared = assertSameOrder(busMessages(moverTrace), busMessages(responderTrace));
        assertTrue(shared.stream().anyMatch(m -> m.startsWith("move/"))
                && shared.stream().anyMatch(m -> m.startsWith("done/")), "both traced moves and dones: " + shared);
    }

    /**
     * Two testers' traces hold every message once, and in the same order from the first message both have (each
     * trace starts when its tester's engine started); returns the messages both have, in that order.
     */
    private static List<String> assertSameOrder(List<String> a, List<String> b) {
        assertEquals(new HashSet<>(a).size(), a.size(), "every message once in the first trace");
        assertEquals(new HashSet<>(b).size(), b.size(), "every message once in the second trace");
        int fromA = a.indexOf(b.get(0));
        int fromB = b.indexOf(a.get(0));
        assertTrue(fromA >= 0 || fromB >= 0, "the traces share messages: " + a.subList(0, 5) + " " + b.subList(0, 5));
        List<String> restA = a.subList(Math.max(0, fromA), a.size());
        List<String> restB = b.subList(Math.max(0, fromB), b.size());
        int overlap = Math.min(restA.size(), restB.size());
        // both PASSED 60 units: a move at most 15 units after each done (e <= 15), its done at most 8 after it
        // (x <= 8), so at least 2 of each; how many more (and how many clock messages) is the machine's business
        assertTrue(overlap >= 4, "moves, dones and the clocks' messages: " + overlap);
        assertEquals(restA.subList(0, overlap), restB.subList(0, overlap));
        return restA.subList(0, overlap);
    }

    /** The bus lines of a trace, as channel/sender/sequence, in the order written. */
    private static List<String> busMessages(Path trace) throws java.io.IOException {
        Pattern bus = Pattern.compile("\\{\"kind\":\"bus\",\"channel\":\"([^\"]+)\",\"sender\":\"([^\"]+)\","
                + "\"sequence\":(\\d+),");
        List<String> messages = new ArrayList<>();
        for (String line : Files.readAllLines(trace)) {
            Matcher m = bus.matcher(line);
            if (m.lookingAt()) {
                messages.add(m.group(1) + "/" + m.group(2) + "/" + m.group(3));
            }
        }
        return messages;
    }
}
