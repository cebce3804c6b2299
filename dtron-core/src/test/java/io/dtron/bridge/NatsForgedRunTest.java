package io.dtron.bridge;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.api.DtronOptions;
import io.dtron.api.DtronStats;
import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.api.internal.proto.Sync;
import io.dtron.bus.internal.NatsTransport;
import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.testadapter.TickerAdapterMain;
import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.Waits;
import io.nats.client.Connection;
import io.nats.client.JetStream;
import io.nats.client.JetStreamManagement;
import io.nats.client.Message;
import io.nats.client.Nats;
import io.nats.client.Subscription;
import io.nats.client.api.MessageInfo;
import io.nats.client.impl.Headers;
import io.nats.client.impl.NatsMessage;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Issue 23, "a bus no one else can speak on": while the bundled ticker model runs in real time on a NATS bus
 * against the ticker adapter (another JVM), a client of the same server publishes a copy of a real tick with
 * another sequence, the same tick again, a reset input in the tester's name, the tester's and the adapter's leave
 * and a stranger's join. On a bus with a secret the run passes, and the tester counts exactly these messages as
 * rejected, without changing its members; on a bus without one the same messages end a correct run otherwise.
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class NatsForgedRunTest {
    private static final Path MODEL = Path.of("../models/src/main/resources/io/dtron/models/ticker.xml");
    private static final String SECRET = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";
    /** 60 units of 100 ms: the ticker's tolerance of 2 units (200 ms) holds for a fresh JVM on a loaded machine. */
    private static final long UNIT_MICROS = 100_000;
    private static final long UNITS = 60;

    @TempDir
    Path dir;

    @Test
    void withTheSecretTheForgedMessagesAreRejectedAndTheRunPasses() throws Exception {
        Outcome outcome = runWithForgeries(true);
        assertEquals(Verdict.PASSED, outcome.result().verdict(), outcome.result().explanation());
        DtronStats stats = outcome.stats();
        assertEquals(5, stats.getRejected(Reason.UNAUTHENTICATED), stats.toString());
        assertEquals(1, stats.getRejected(Reason.REPLAYED), stats.toString());
        assertEquals(6, stats.getRejectedTotal(), stats.toString());
        assertEquals(Set.of(outcome.tester(), "ticker"), Set.copyOf(outcome.members()), "members unchanged");
    }

    /** The control: the same messages are an attack that works on a bus without the secret. */
    @Test
    void withoutTheSecretTheSameMessagesSpoilACorrectRun() throws Exception {
        Outcome outcome = runWithForgeries(false);
        assertNotEquals(Verdict.PASSED, outcome.result().verdict(), outcome.result().explanation());
        assertEquals(0, outcome.stats().getRejected(Reason.UNAUTHENTICATED) + outcome.stats()
                .getRejected(Reason.REPLAYED), "nothing on this bus carries a code: " + outcome.stats());
    }

    /**
     * A client without the secret keeps the last run's signed reset and stop as they were published, and publishes
     * them again, still fresh, while a new tester runs against a new ticker: they are of another run, so the ticker
     * neither restarts nor stops, and the run passes.
     */
    @Test
    void theLastRunsResetAndStopPublishedAgainInTheNextRunChangeNothing() throws Exception {
        try (NatsServer server = NatsServer.start(dir);
                Connection raw = Nats.connect(server.url())) {
            SecureTickerBus ticker = SecureTickerBus.of("replayed", server);
            String bus = ticker.bus();
            Subscription resets = raw.subscribe("dtron." + bus + ".c.reset");
            Subscription stops = raw.subscribe("dtron." + bus + ".c.dtron_stop");
            raw.flush(Duration.ofSeconds(10));
            ticker.passingRun(this, server, "first");
            Message reset = resets.nextMessage(Duration.ofSeconds(30));
            Message stop = stops.nextMessage(Duration.ofSeconds(30));
            assertTrue(reset != null && stop != null, "the first run reset the ticker and stopped");
            TestResult second = runAgainstANewTicker(ticker.network(), ticker.testInterface(), bus, server,
                    ticker.options(), SECRET, "second",
                    (js, tick, tester) -> {
                        publish(js, reset.getSubject(), new Headers(reset.getHeaders()).put("Nats-Msg-Id", "again-1"),
                                reset.getData());
                        publish(js, stop.getSubject(), new Headers(stop.getHeaders()).put("Nats-Msg-Id", "again-2"),
                                stop.getData());
                    }, 0).result();
            assertEquals(Verdict.PASSED, second.verdict(), second.explanation());
        }
    }

    /**
     * A client without the secret keeps every message of a finished run as the stream stored it, the tester's run
     * start among them, and publishes them all again, still fresh, after a tester joined the bus to join the next
     * run: the joining tester learned their senders' numbers from the stream when it joined, so it drops each of them
     * as replayed, takes no run and sees no member come or go.
     */
    @Test
    void theLastRunsMessagesPublishedAgainAfterATesterJoinedAreReplayedForIt() throws Exception {
        try (NatsServer server = NatsServer.start(dir);
                Connection raw = Nats.connect(server.url())) {
            SecureTickerBus ticker = SecureTickerBus.of("rejoined", server);
            ticker.passingRun(this, server, "first");
            JetStreamManagement management = raw.jetStreamManagement();
            String stream = "DTRON_" + ticker.bus();
            long last = management.getStreamInfo(stream).getStreamState().getLastSequence();
            List<MessageInfo> captured = new ArrayList<>();
            for (long sequence = 1; sequence <= last; sequence++) {
                captured.add(management.getMessage(stream, sequence));
            }
            assertTrue(captured.stream().anyMatch(m -> m.getSubject().endsWith(".c.dtron_start")),
                    "the first run's start is among its messages");
            try (BusBridge joining = BusBridge.join(ticker.testInterface(), ticker.options()
                    .memberName("joining"))) {
                JetStream js = raw.jetStream();
                for (MessageInfo message : captured) {
                    publish(js, message.getSubject(), new Headers(message.getHeaders()).put("Nats-Msg-Id",
                            "again-" + message.getSeq()), message.getData());
                }
                Waits.await("the joining tester read the messages published again").until(
                        () -> joining.run().stats().getRejectedTotal() >= captured.size());
                DtronStats stats = joining.run().stats();
                assertEquals(captured.size(), stats.getRejected(Reason.REPLAYED), stats.toString());
                assertEquals(captured.size(), stats.getRejectedTotal(), stats.toString());
                assertEquals(-1, joining.run().awaitRun(Duration.ZERO), "the joining tester took no run");
                assertEquals(List.of("joining"), joining.run().members(), "no member came or went");
            }
        }
    }

    /** The ticker model on a bus of its own with the secret, of a test's server. */
    private record SecureTickerBus(Network network, TestInterface testInterface, String bus,
            DtronOptions.Builder options) {
        static SecureTickerBus of(String prefix, NatsServer server) throws Exception {
            Network network = ModelLoader.load(MODEL);
            String bus = prefix + "-" + UUID.randomUUID().toString().substring(0, 8);
            return new SecureTickerBus(network, TestInterface.fromNames(network), bus, DtronOptions.builder()
                    .clusterName(bus).natsServers(server.url()).secret(SECRET));
        }

        /** A run of a tester against a new ticker named {@code name}, which passes. */
        void passingRun(NatsForgedRunTest test, NatsServer server, String name) throws Exception {
            TestResult result = test.runAgainstANewTicker(network, testInterface, bus, server, options, SECRET, name,
                    null, 0).result();
            assertEquals(Verdict.PASSED, result.verdict(), result.explanation());
        }
    }

    /** What a client publishes during a run, once a tick came. */
    @FunctionalInterface
    private interface Meddling {
        void publish(JetStream js, Message tick, String tester) throws Exception;
    }

    private record Outcome(TestResult result, DtronStats stats, String tester, List<String> members) {
    }

    private Outcome runWithForgeries(boolean secure) throws Exception {
        Network network = ModelLoader.load(MODEL);
        TestInterface testInterface = TestInterface.fromNames(network);
        String bus = "forged-" + UUID.randomUUID().toString().substring(0, 8);
        try (NatsServer server = NatsServer.start(dir)) {
            DtronOptions.Builder options = DtronOptions.builder().clusterName(bus).natsServers(server.url());
            if (secure) {
                options.secret(SECRET);
            } else {
                options.insecure(true);
            }
            return runAgainstANewTicker(network, testInterface, bus, server, options, secure ? SECRET : "insecure",
                    "ticker", (js, tick, tester) -> forge(js, bus, tick, tester), secure ? 6 : 0);
        }
    }

    /**
     * A run of the tester against a ticker in a JVM of its own (named {@code name}, with {@code secret} or
     * "insecure"); {@code meddling} (or none) publishes once a tick came, and the outcome is taken once the tester
     * rejected at least {@code rejected} messages (its receive thread has its own pace).
     */
    private Outcome runAgainstANewTicker(Network network, TestInterface testInterface, String bus, NatsServer server,
            DtronOptions.Builder options, String secret, String name, Meddling meddling, long rejected)
            throws Exception {
        try (Connection raw = Nats.connect(server.url());
                ChildJvm ticker = ChildJvm.start(TickerAdapterMain.class, dir.resolve(name + ".log"), bus, name,
                        "correct", "1", server.url(), secret)) {
            ticker.awaitOutput("joined", Duration.ofSeconds(60));
            try (BusBridge bridge = BusBridge.connect(testInterface, options)) {
                assertTrue(bridge.run().awaitAdapters(1, Duration.ofSeconds(60)), "the ticker joined");
                Subscription ticks = raw.subscribe("dtron." + bus + ".c.tick");
                raw.flush(Duration.ofSeconds(10));
                CompletableFuture<TestResult> run = CompletableFuture.supplyAsync(() -> new OnlineTester(network,
                        testInterface, bridge, new TestOptions(1, UNIT_MICROS, UNITS, DelayPolicy.EAGER, 0, false))
                        .run());
                if (meddling != null) {
                    Message tick = ticks.nextMessage(Duration.ofSeconds(60)); // the run is under way
                    assertTrue(tick != null, "a tick during the run");
                    meddling.publish(raw.jetStream(), tick, bridge.run().memberId());
                }
                TestResult result = run.get(2, TimeUnit.MINUTES);
                Waits.await("the tester read the forged messages").until(
                        () -> bridge.run().stats().getRejectedTotal() >= rejected);
                return new Outcome(result, bridge.run().stats(), bridge.run().memberId(), bridge.run().members());
            }
        }
    }

    /** What a client of the server without the secret publishes: five forged messages and one replayed. */
    private static void forge(JetStream js, String bus, Message tick, String tester) throws Exception {
        String ticker = tick.getHeaders().getFirst(NatsTransport.SENDER);
        Sync real = Sync.parseFrom(tick.getData());
        String channels = "dtron." + bus + ".c.";
        String presence = "dtron." + bus + ".p";
        // the tick again, as another message of the ticker's
        publish(js, tick.getSubject(), new Headers().put(NatsTransport.SENDER, ticker),
                real.toBuilder().setSequence(real.getSequence() + 1_000_000).build().toByteArray());
        // the tick as it was, under another Nats-Msg-Id so that the stream stores it again
        publish(js, tick.getSubject(), new Headers(tick.getHeaders()).put("Nats-Msg-Id", "replayed"), tick.getData());
        // a reset in the tester's name, which would restart the ticker
        long now = System.currentTimeMillis() * 1_000_000L;
        publish(js, channels + "reset", new Headers().put(NatsTransport.SENDER, tester), Sync.newBuilder()
                .setName("reset").setSender(tester).setSequence(1_000_000).setPublishTimeNs(now).setEventTimeNs(now)
                .setRunId(real.getRunId()).build().toByteArray());
        // the tester leaving (the ticker stops when a member leaves), the ticker leaving, and a stranger joining
        for (String[] who : new String[][] {{tester, "leave"}, {ticker, "leave"}, {"stranger", "join"}}) {
            publish(js, presence, new Headers().put(NatsTransport.SENDER, who[0]).put(NatsTransport.PRESENCE, who[1]),
                    new byte[0]);
        }
    }

    private static void publish(JetStream js, String subject, Headers headers, byte[] data) throws Exception {
        js.publish(NatsMessage.builder().subject(subject).headers(headers).data(data).build());
    }
}
