package io.dtron.models.relay;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.cli.DtronCommand;
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
     * 100 ms per time unit: the models' narrowest windows (3 to 4 units) are then wider than what a busy machine
     * adds to three JVMs' timing (a relay 26 ms late, a tester held up 200 ms were seen at 20 ms per unit).
     */
    private static final String UNIT_MICROS = "100000";

    private static String cluster() {
        return "distributed-" + UUID.randomUUID().toString().substring(0, 8);
    }

    private static ChildJvm tester(Path dir, String name, String model, String cluster, String address,
            String... more) throws Exception {
        List<String> args = new ArrayList<>(List.of("run", MODELS.resolve(model).toString(), "--cluster", cluster,
                "--bind", address, "--members", MEMBERS, "--timeunit", UNIT_MICROS, "--timeout", "60", "--delay-policy",
                "eager", "--seed", "7", "--wait-timeout", "90"));
        args.addAll(List.of(more));
        return ChildJvm.start(DtronCommand.class, dir.resolve(name + ".log"), args.toArray(String[]::new));
    }

    /** The exit codes and outputs of the relay's two testers, with the relay's output. */
    private record Relay(int port1, int port2, String port1Output, String port2Output, String relayOutput) {
        String all() {
            return port1Output + port2Output + relayOutput;
        }
    }

    /** Runs both ports' testers against a relay of the variant, each port in a JVM of its own. */
    private static Relay relay(Path dir, String variant) throws Exception {
        String cluster = cluster();
        try (ChildJvm port1 = tester(dir, "port1", "relay/port1.xta", cluster, "127.0.0.1", "--testers", "2");
                ChildJvm port2 = tester(dir, "port2", "relay/port2.xta", cluster, "127.0.0.2", "--join");
                ChildJvm relay = ChildJvm.start(RelayAdapters.class, dir.resolve("relay.log"), cluster, "127.0.0.3",
                        MEMBERS, variant)) {
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
    }

    @Test
    void aLateResponseFailsAtPortTwoAndEndsPortOneWithTheReason(@TempDir Path dir) throws Exception {
        Relay r = relay(dir, "late");
        assertEquals(2, r.port2(), r.all());
        // the late response is seen late, or not by its deadline (after how the request was taken)
        assertTrue(r.port2Output().matches("(?s).*FAILED: (?:[^\n]*?; then )?(?:output resp\\(\\) observed at"
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
        try (ChildJvm mover = tester(dir, "mover", "conversation/mover.xta", cluster, "127.0.0.1", "--testers", "2",
                "--trace", moverTrace.toString());
                ChildJvm responder = tester(dir, "responder", "conversation/responder.xta", cluster, "127.0.0.2",
                        "--join", "--trace", responderTrace.toString())) {
            int first = mover.waitFor(WAIT);
            int second = responder.waitFor(WAIT);
            assertEquals(0, first, mover.output() + responder.output());
            assertEquals(0, second, responder.output() + mover.output());
            assertTrue(mover.output().contains("PASSED"), mover.output());
            assertTrue(responder.output().contains("PASSED"), responder.output());
        }
        List<String> a = busMessages(moverTrace);
        List<String> b = busMessages(responderTrace);
        assertEquals(new HashSet<>(a).size(), a.size(), "every message once in the mover's trace");
        assertEquals(new HashSet<>(b).size(), b.size(), "every message once in the responder's trace");
        // the traces start when each engine started: from the first message both have, the order is the same
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
