package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.api.internal.SyncCodec;
import io.dtron.bus.internal.MessageCodes;
import io.dtron.bus.internal.NatsTransport;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.LogCapture;
import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.Waits;
import io.nats.client.Connection;
import io.nats.client.JetStream;
import io.nats.client.Message;
import io.nats.client.Nats;
import io.nats.client.api.PublishAck;
import io.nats.client.impl.Headers;
import io.nats.client.impl.NatsMessage;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.Deque;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The bus's secret on a real {@code nats-server} (security.md): a client that reaches the server but lacks the
 * secret cannot speak on the bus. Its forged channel messages and presence are dropped before delivery and
 * membership, counted as rejected and logged once per sender and reason; a valid message published again is
 * dropped as replayed, one whose sender time is ten minutes off as stale. The server's own authentication keeps a
 * client without credentials from even connecting.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class NatsSecurityTest {
    private static final IDtronChannel ORDER = IDtronChannel.of("order", "n");
    static final String SECRET = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";

    @TempDir
    Path dir;

    private static DtronOptions.Builder member(NatsServer server, String bus, String name) {
        return DtronOptions.builder().clusterName(bus).memberName(name).natsServers(server.url()).secret(SECRET);
    }

    private static byte[] order(int n, String sender) {
        return SyncCodec.encode("order", Map.of("n", n), sender, n, 1);
    }

    /** Publishes a message through JetStream and returns the stream's acknowledgement. */
    private static PublishAck publish(JetStream js, String subject, Headers headers, byte[] data) throws Exception {
        return js.publish(NatsMessage.builder().subject(subject).headers(headers).data(data).build());
    }

    /** The headers of a message signed with {@code codes}, as a member with that secret makes them. */
    private static Headers signed(MessageCodes codes, String subject, String sender, long seq, long time,
            String presence, byte[] data) {
        Headers headers = new Headers().put(NatsTransport.SENDER, sender).put(MessageCodes.SEQ, Long.toString(seq))
                .put(MessageCodes.TIME, Long.toString(time));
        if (presence != null) {
            headers.put(NatsTransport.PRESENCE, presence);
        }
        return headers.put(MessageCodes.MAC, codes.code(subject, sender, Long.toString(seq), Long.toString(time),
                presence, null, data));
    }

    /** Publishes a message as a holder of {@link #SECRET} makes it, at the current time. */
    static void publishSigned(JetStream js, String subject, String sender, long seq, byte[] data) throws Exception {
        MessageCodes codes = MessageCodes.forSecret(SECRET.getBytes(StandardCharsets.UTF_8));
        publish(js, subject, signed(codes, subject, sender, seq, System.currentTimeMillis() * 1_000_000L, null, data),
                data);
    }

    /** What a test opened, closed after it, the last first. */
    private final Deque<AutoCloseable> opened = new ArrayDeque<>();

    private <T extends AutoCloseable> T opened(T closeable) {
        opened.push(closeable);
        return closeable;
    }

    @AfterEach
    void closeOpened() throws Exception {
        while (!opened.isEmpty()) {
            opened.pop().close();
        }
    }

    /**
     * A test's own {@code nats-server} and bus: a tester with the secret that listens to {@code order} into
     * {@code inbox}, an adapter with the secret (or null), and a raw client of the server without the secret.
     */
    private record SecureBus(String name, Inbox inbox, Dtron tester, Dtron adapter, Connection raw, JetStream js) {
        /** The subject of channel {@code order} on this bus. */
        String channel() {
            return "dtron." + name + ".c.order";
        }

        /** The subject of presence on this bus. */
        String presence() {
            return "dtron." + name + ".p";
        }

        /** The raw client's subscription to channel {@code order}, in place on the server. */
        io.nats.client.Subscription capture() throws Exception {
            io.nats.client.Subscription capture = raw.subscribe(channel());
            raw.flush(Duration.ofSeconds(10));
            return capture;
        }
    }

    private SecureBus secureBus(String what, boolean withAdapter) throws Exception {
        NatsServer server = opened(NatsServer.start(dir));
        String name = TestClusters.uniqueName(what);
        Inbox inbox = new Inbox(ORDER);
        Dtron tester = opened(Dtron.connect(member(server, name, "tester").channels(List.of(ORDER)).build()));
        tester.addDtronListener(inbox);
        Dtron adapter = withAdapter ? opened(Dtron.connect(member(server, name, "adapter").build())) : null;
        Connection raw = opened(Nats.connect(server.url()));
        return new SecureBus(name, inbox, tester, adapter, raw, raw.jetStream());
    }

    @Test
    void forgedMessagesOfAClientWithoutTheSecretAreDroppedCountedAndChangeNoView() throws Exception {
        try (LogCapture log = new LogCapture(NatsTransport.class)) {
            SecureBus bus = secureBus("forged", true);
            Dtron tester = bus.tester();
            Dtron adapter = bus.adapter();
            JetStream js = bus.js();
            String channel = bus.channel();
            String presence = bus.presence();
            assertTrue(tester.awaitMembers(2, Duration.ofSeconds(30)), tester.getMembers().toString());
            List<List<String>> changes = new CopyOnWriteArrayList<>();
            tester.addMembershipListener((members, joined, left) -> changes.add(List.of(String.join(",", joined),
                    String.join(",", left))));
            long now = System.currentTimeMillis() * 1_000_000L;
            // an output in the adapter's name, without a code
            publish(js, channel, new Headers().put(NatsTransport.SENDER, "adapter"), order(666, "adapter"));
            // with a code made up
            publish(js, channel, new Headers().put(NatsTransport.SENDER, "adapter")
                    .put(MessageCodes.SEQ, "1").put(MessageCodes.TIME, Long.toString(now))
                    .put(MessageCodes.MAC, "0".repeat(64)), order(667, "adapter"));
            // with the code of a guessed secret
            MessageCodes guess = MessageCodes.forSecret("guess".getBytes(StandardCharsets.UTF_8));
            publish(js, channel, signed(guess, channel, "adapter", 2, now, null, order(668, "adapter")),
                    order(668, "adapter"));
            // a member joining that is none, and a real member leaving
            publish(js, presence, new Headers().put(NatsTransport.SENDER, "ghost").put(NatsTransport.PRESENCE,
                    "join"), new byte[0]);
            publish(js, presence, new Headers().put(NatsTransport.SENDER, "adapter").put(NatsTransport.PRESENCE,
                    "leave"), new byte[0]);

            adapter.send(ORDER.constructValued(Map.of("n", 7)));
            IDtronChannelValued first = bus.inbox().take(); // after every forged one in the stream's order
            assertEquals(7, first.getVariables().get("n"), "no forged order came through: " + first);
            assertEquals("adapter", first.getSender());
            DtronStats stats = tester.getStats();
            assertEquals(5, stats.getRejected(Reason.UNAUTHENTICATED), stats.toString());
            assertEquals(5, stats.getRejectedTotal(), stats.toString());
            assertTrue(stats.toString().contains("unauthenticated 5"), stats.toString());
            assertEquals(List.of("tester", "adapter"), tester.getMembers());
            assertFalse(changes.stream().anyMatch(c -> c.get(0).contains("ghost") || c.get(1).contains("adapter")),
                    "the forged presence changed the view: " + changes);
            List<String> lines = log.messages().stream().filter(m -> m.startsWith("tester: dropped")).toList();
            assertEquals(2, lines.size(), "one line per sender and reason: " + lines);
            assertTrue(lines.get(0).contains("from adapter, unauthenticated"), lines.get(0));
            assertTrue(lines.get(1).contains("from ghost, unauthenticated"), lines.get(1));
            assertFalse(log.anyStackTrace());
        }
    }

    @Test
    void aValidMessagePublishedAgainIsDroppedAsReplayed() throws Exception {
        SecureBus bus = secureBus("replay", true);
        Dtron tester = bus.tester();
        Dtron adapter = bus.adapter();
        Inbox inbox = bus.inbox();
        io.nats.client.Subscription capture = bus.capture();
        adapter.send(ORDER.constructValued(Map.of("n", 1)));
        assertEquals(1, inbox.take().getVariables().get("n"));
        Message captured = capture.nextMessage(Duration.ofSeconds(20));
        assertTrue(captured != null && captured.hasHeaders(), "the subscriber saw the message");
        JetStream js = bus.js();
        // as it was: the stream itself recognises its Nats-Msg-Id and does not store it again
        assertTrue(publish(js, captured.getSubject(), captured.getHeaders(), captured.getData())
                .isDuplicate());
        // with another id, stored again: the members drop it
        Headers again = new Headers(captured.getHeaders()).put("Nats-Msg-Id", "replay-1");
        assertFalse(publish(js, captured.getSubject(), again, captured.getData()).isDuplicate());

        adapter.send(ORDER.constructValued(Map.of("n", 2)));
        assertEquals(2, inbox.take().getVariables().get("n"), "the replayed 1 was not delivered again");
        DtronStats stats = tester.getStats();
        assertEquals(1, stats.getRejected(Reason.REPLAYED), stats.toString());
        assertEquals(1, stats.getRejectedTotal(), stats.toString());
        // the adapter's receive thread reads the stream at its own pace
        Waits.await("the adapter drops its own message replayed").until(
                () -> adapter.getStats().getRejected(Reason.REPLAYED) >= 1);
        assertEquals(1, adapter.getStats().getRejectedTotal(), adapter.getStats().toString());
    }

    /**
     * A member that joins later learns the numbers of the messages before its join from the stream, without
     * delivering them: a message published before it joined and published again after is replayed for it too.
     */
    @Test
    void aMessageFromBeforeAMemberJoinedPublishedAgainIsReplayedForIt() throws Exception {
        SecureBus bus = secureBus("late", true);
        io.nats.client.Subscription capture = bus.capture();
        bus.adapter().send(ORDER.constructValued(Map.of("n", 1)));
        assertEquals(1, bus.inbox().take().getVariables().get("n"));
        Message captured = capture.nextMessage(Duration.ofSeconds(20));
        assertTrue(captured != null && captured.hasHeaders(), "the subscriber saw the message");
        Inbox lateInbox = new Inbox(ORDER);
        Dtron late = opened(Dtron.connect(DtronOptions.builder().clusterName(bus.name()).memberName("late")
                .natsServers(bus.raw().getConnectedUrl()).secret(SECRET).channels(List.of(ORDER)).build()));
        late.addDtronListener(lateInbox);
        Headers again = new Headers(captured.getHeaders()).put("Nats-Msg-Id", "replay-late");
        assertFalse(publish(bus.js(), captured.getSubject(), again, captured.getData()).isDuplicate());

        bus.adapter().send(ORDER.constructValued(Map.of("n", 2)));
        assertEquals(2, lateInbox.take().getVariables().get("n"), "neither the 1 before the join nor its copy came");
        assertEquals(1, late.getStats().getRejected(Reason.REPLAYED), late.getStats().toString());
        assertEquals(1, late.getStats().getRejectedTotal(), late.getStats().toString());
    }

    /**
     * A client without the secret that sees a member's messages cannot publish first under the member's next
     * {@code Nats-Msg-Id}, which would have the stream drop the member's message as its duplicate: whatever it
     * derives from the ids it saw (the next numbers, decimal or hexadecimal), the member's next message is stored
     * and delivered.
     */
    @Test
    void noOneCanTakeAMembersNextMessageIdFirst() throws Exception {
        SecureBus bus = secureBus("squat", true);
        Dtron adapter = bus.adapter();
        Inbox inbox = bus.inbox();
        io.nats.client.Subscription capture = bus.capture();
        for (int n = 1; n <= 3; n++) {
            adapter.send(ORDER.constructValued(Map.of("n", n)));
            assertEquals(n, inbox.take().getVariables().get("n"));
        }
        java.util.Set<String> seen = new java.util.HashSet<>();
        String last = null;
        for (int n = 1; n <= 3; n++) {
            Message captured = capture.nextMessage(Duration.ofSeconds(20));
            assertTrue(captured != null && captured.hasHeaders(), "the subscriber saw message " + n);
            last = captured.getHeaders().getFirst("Nats-Msg-Id");
            assertTrue(seen.add(last), "ids differ: " + seen);
        }
        String prefix = last.substring(0, last.lastIndexOf('-') + 1);
        String tail = last.substring(last.lastIndexOf('-') + 1);
        List<String> guesses = new java.util.ArrayList<>();
        for (int ahead = 1; ahead <= 20; ahead++) {
            if (tail.matches("\\d{1,18}")) {
                guesses.add(prefix + (Long.parseLong(tail) + ahead));
            }
            guesses.add(prefix + new java.math.BigInteger(tail, 16).add(java.math.BigInteger.valueOf(ahead))
                    .toString(16));
        }
        for (String guess : guesses) {
            publish(bus.js(), bus.channel(), new Headers().put(NatsTransport.SENDER, "adapter")
                    .put("Nats-Msg-Id", guess), order(666, "adapter"));
        }
        adapter.send(ORDER.constructValued(Map.of("n", 4)));
        assertEquals(4, inbox.take().getVariables().get("n"), "the member's next message was stored and delivered");
        assertEquals(guesses.size(), bus.tester().getStats().getRejected(Reason.UNAUTHENTICATED),
                bus.tester().getStats().toString());
    }

    /**
     * A client without the secret publishes, with the NATS protocol itself, a message whose headers read as the
     * server's status (an idle heartbeat): the client library keeps it from the consumer's handler, and the consumer
     * made anew from it waited for it for ever. Now it is counted as unauthenticated and the consumer is made from
     * the message after it: the adapter's next order still comes.
     */
    @Test
    void aMessageThatReadsAsTheServersStatusDoesNotStallAMember() throws Exception {
        SecureBus bus = secureBus("status", true);
        java.net.URI url = java.net.URI.create(bus.raw().getConnectedUrl());
        try (java.net.Socket socket = new java.net.Socket(url.getHost(), url.getPort())) {
            java.io.BufferedReader in = new java.io.BufferedReader(new java.io.InputStreamReader(
                    socket.getInputStream(), StandardCharsets.US_ASCII));
            assertTrue(in.readLine().startsWith("INFO "), "the server greets");
            String headers = "NATS/1.0 100 Idle Heartbeat\r\n\r\n";
            String payload = "x";
            String frames = "CONNECT {\"verbose\":false,\"headers\":true,\"protocol\":1}\r\n"
                    + "HPUB " + bus.channel() + " " + headers.length() + " " + (headers.length() + payload.length())
                    + "\r\n" + headers + payload + "\r\nPING\r\n";
            socket.getOutputStream().write(frames.getBytes(StandardCharsets.US_ASCII));
            socket.getOutputStream().flush();
            assertEquals("PONG", in.readLine(), "the server took the message");
        }
        bus.adapter().send(ORDER.constructValued(Map.of("n", 9)));
        assertEquals(9, bus.inbox().take().getVariables().get("n"), "the order after it came");
        assertEquals(1, bus.tester().getStats().getRejected(Reason.UNAUTHENTICATED),
                bus.tester().getStats().toString());
    }

    @Test
    void aMessageWhoseSenderTimeIsTenMinutesOffIsStale() throws Exception {
        SecureBus bus = secureBus("stale", false);
        Dtron tester = bus.tester();
        Inbox inbox = bus.inbox();
        JetStream js = bus.js();
        MessageCodes codes = MessageCodes.forSecret(SECRET.getBytes(StandardCharsets.UTF_8));
        String channel = bus.channel();
        long tenMinutes = TimeUnit.MINUTES.toNanos(10);
        long now = System.currentTimeMillis() * 1_000_000L;
        publish(js, channel, signed(codes, channel, "holder", 1, now - tenMinutes, null, order(1, "holder")),
                order(1, "holder"));
        publish(js, channel, signed(codes, channel, "holder", 2, now + tenMinutes, null, order(2, "holder")),
                order(2, "holder"));
        // the same holder of the secret, on time: delivered (the test's codes are the members')
        now = System.currentTimeMillis() * 1_000_000L;
        publish(js, channel, signed(codes, channel, "holder", 3, now, null, order(3, "holder")),
                order(3, "holder"));
        IDtronChannelValued first = inbox.take();
        assertEquals(3, first.getVariables().get("n"), "the stale ones were not delivered");
        assertEquals("holder", first.getSender());
        DtronStats stats = tester.getStats();
        assertEquals(2, stats.getRejected(Reason.STALE), stats.toString());
        assertEquals(2, stats.getRejectedTotal(), stats.toString());
    }

    /**
     * Members with the secret, without any (insecure) and with another secret share a server and a bus name, and
     * each drops the others' messages: none sees another join.
     */
    @Test
    void membersOfAnotherSecretOrNoneAreNeverSeen() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            String bus = TestClusters.uniqueName("mixed");
            DtronOptions.Builder insecure = DtronOptions.builder().clusterName(bus).memberName("insecure")
                    .natsServers(server.url()).insecure(true);
            try (Dtron secure = Dtron.connect(member(server, bus, "secure").build());
                    Dtron none = Dtron.connect(insecure.build());
                    Dtron other = Dtron.connect(member(server, bus, "other").secret("another secret").build())) {
                for (Dtron dtron : List.of(secure, none, other)) {
                    // each has dropped at least the others' joins by the time its own came back, and its
                    // heartbeats every second
                    Waits.await(dtron.getMemberId() + " drops the others").until(
                            () -> dtron.getStats().getRejected(Reason.UNAUTHENTICATED) >= 2);
                    assertEquals(List.of(dtron.getMemberId()), dtron.getMembers());
                }
            }
        }
    }

    @Test
    void aServerWithATokenRefusesAClientWithoutIt() throws Exception {
        try (NatsServer server = NatsServer.startWith(dir, List.of("--auth", "t0ken"))) {
            IOException refused = assertThrows(IOException.class, () -> Nats.connect(server.url()).close());
            assertTrue(String.valueOf(refused.getMessage()).toLowerCase(java.util.Locale.ROOT).contains("author"),
                    refused.toString());
            String bus = TestClusters.uniqueName("token");
            try (Dtron member = Dtron.connect(member(server, bus, "member").natsToken("t0ken").build())) {
                assertEquals(List.of("member"), member.getMembers());
            }
        }
    }
}
