package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testadapter.OrderMemberMain;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.Waits;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The bus on a real {@code nats-server} with JetStream: every member receives every message, its own included, in
 * one order; members see each other join and leave, and a killed member is gone within seconds; bad input is
 * rejected and counted as on JGroups.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class NatsBusTest {
    private static final IDtronChannel ORDER = IDtronChannel.of("order", "n");

    @TempDir
    Path dir;

    private static DtronOptions.Builder nats(NatsServer server, String cluster, String member) {
        return DtronOptions.builder().clusterName(cluster).memberName(member).natsServers(server.url());
    }

    @Test
    void membersInOneJvmSeeOneOrderAndEachOtherJoinAndLeave() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            String cluster = TestClusters.uniqueName("order");
            Inbox inboxA = new Inbox(ORDER);
            Inbox inboxB = new Inbox(ORDER);
            try (Dtron a = Dtron.connect(nats(server, cluster, "a").build())) {
                a.addDtronListener(inboxA);
                try (Dtron b = Dtron.connect(nats(server, cluster, "b").build())) {
                    b.addDtronListener(inboxB);
                    assertTrue(a.awaitMembers(2, Duration.ofSeconds(10)), "a sees b: " + a.getMembers());
                    assertTrue(b.awaitMembers(2, Duration.ofSeconds(10)), "b sees a: " + b.getMembers());
                    assertEquals(List.of("a", "b"), a.getMembers(), "oldest first");
                    assertEquals(a.getMembers(), b.getMembers());
                    Thread senderB = new Thread(() -> {
                        for (int n = 1; n <= 200; n++) {
                            b.send(ORDER.constructValued(Map.of("n", n)));
                        }
                    });
                    senderB.start();
                    for (int n = 1; n <= 200; n++) {
                        a.send(ORDER.constructValued(Map.of("n", n)));
                    }
                    senderB.join();
                    List<String> seenA = new ArrayList<>();
                    List<String> seenB = new ArrayList<>();
                    for (int i = 0; i < 400; i++) {
                        IDtronChannelValued x = inboxA.take();
                        seenA.add(x.getSender() + ":" + x.getVariables().get("n"));
                        IDtronChannelValued y = inboxB.take();
                        seenB.add(y.getSender() + ":" + y.getVariables().get("n"));
                    }
                    assertEquals(seenA, seenB, "one order at both members");
                    assertTrue(seenA.contains("a:200") && seenA.contains("b:200"), "own and other's messages");
                    assertEquals(400, seenA.stream().distinct().count(), "none twice");
                }
                Waits.await("b gone").until(a::getMembers, List.of("a")::equals);
            }
        }
    }

    /**
     * A member that joins a bus whose stream holds messages reads it from a start time; when the server loses its
     * consumer (here: every consumer of the stream deleted), it is made anew from a sequence, and the member hears
     * the next order.
     */
    @Test
    void aMemberThatJoinedLaterHearsTheBusAfterItsConsumerWasMadeAnew() throws Exception {
        try (NatsServer server = NatsServer.start(dir);
                io.nats.client.Connection raw = io.nats.client.Nats.connect(server.url())) {
            String cluster = TestClusters.uniqueName("anew");
            Inbox inbox = new Inbox(ORDER);
            try (Dtron a = Dtron.connect(nats(server, cluster, "a").build());
                    Dtron b = Dtron.connect(nats(server, cluster, "b").build())) { // the stream holds a's messages
                b.addDtronListener(inbox);
                assertTrue(b.awaitMembers(2, Duration.ofSeconds(10)), "b sees a: " + b.getMembers());
                io.nats.client.JetStreamManagement management = raw.jetStreamManagement();
                for (String consumer : management.getConsumerNames("DTRON_" + cluster)) {
                    management.deleteConsumer("DTRON_" + cluster, consumer);
                }
                a.send(ORDER.constructValued(Map.of("n", 1)));
                IDtronChannelValued first = inbox.poll(Waits.TIMEOUT.toMillis());
                assertTrue(first != null, "b heard a again");
                assertEquals(1, first.getVariables().get("n"));
            }
        }
    }

    @Test
    void aKilledMemberIsGoneWithinSecondsAndProcessesShareOneOrder() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            String cluster = TestClusters.uniqueName("procs");
            List<ChildJvm> children = new ArrayList<>();
            try {
                for (int i = 0; i < 2; i++) {
                    children.add(ChildJvm.start(OrderMemberMain.class, dir.resolve("m" + i + ".log"), cluster,
                            "m" + i, dir.resolve("m" + i + ".txt").toString(), "1000", "2", server.url()));
                }
                for (int i = 0; i < 2; i++) {
                    assertEquals(0, children.get(i).waitFor(Duration.ofSeconds(90)), children.get(i).output());
                }
            } finally {
                children.forEach(ChildJvm::close);
            }
            List<String> first = Files.readAllLines(dir.resolve("m0.txt"));
            assertEquals(2000, first.size());
            assertEquals(first, Files.readAllLines(dir.resolve("m1.txt")), "one order in both processes");

            try (Dtron watcher = Dtron.connect(nats(server, cluster, "watcher").build());
                    ChildJvm victim = ChildJvm.start(OrderMemberMain.class, dir.resolve("victim.log"), cluster,
                            "victim", dir.resolve("victim.txt").toString(), "1", "3", server.url())) {
                assertTrue(watcher.awaitMembers(2, Duration.ofSeconds(60)), watcher.getMembers().toString());
                assertTrue(watcher.getMembers().contains("victim"));
                victim.kill();
                // a member silent for 4 s (NatsSettings.SILENCE) is dropped: gone within seconds; how many the
                // machine's load decides, so the wait is the tests' generous one
                Waits.await("the killed member dropped").until(() -> !watcher.getMembers().contains("victim"));
            }
        }
    }

    @Test
    void aServerWithAUserTakesOnlyMembersWithItsPassword() throws Exception {
        try (NatsServer server = NatsServer.startWith(dir, List.of("--user", "lab", "--pass", "s3cret"))) {
            String cluster = TestClusters.uniqueName("auth");
            DtronException refused = org.junit.jupiter.api.Assertions.assertThrows(DtronException.class,
                    () -> Dtron.connect(nats(server, cluster, "nobody").build()));
            assertTrue(String.valueOf(refused.getCause()).toLowerCase(java.util.Locale.ROOT).contains("author"),
                    "the server refused the member: " + refused.getCause());
            DtronException wrong = org.junit.jupiter.api.Assertions.assertThrows(DtronException.class,
                    () -> Dtron.connect(nats(server, cluster, "guesser").natsUser("lab", "guess").build()));
            assertTrue(String.valueOf(wrong.getCause()).toLowerCase(java.util.Locale.ROOT).contains("author"),
                    String.valueOf(wrong.getCause()));
            try (Dtron member = Dtron.connect(nats(server, cluster, "member").natsUser("lab", "s3cret").build())) {
                assertEquals(List.of("member"), member.getMembers());
                assertTrue(member.toString().contains("member"));
            }
        }
    }

    @Test
    void aServerWithAnNkeyUserTakesTheMemberWithItsSeed() throws Exception {
        io.nats.client.NKey user = io.nats.client.NKey.createUser(null);
        Path seed = Files.writeString(dir.resolve("user.nk"), new String(user.getSeed()) + "\n");
        Path config = Files.writeString(dir.resolve("nkey.conf"), "authorization { users = [ { nkey: "
                + new String(user.getPublicKey()) + " } ] }\n");
        try (NatsServer server = NatsServer.startWith(dir, List.of("-c", config.toString()))) {
            String cluster = TestClusters.uniqueName("nkey");
            org.junit.jupiter.api.Assertions.assertThrows(DtronException.class,
                    () -> Dtron.connect(nats(server, cluster, "nobody").build()));
            try (Dtron member = Dtron.connect(nats(server, cluster, "seeded").natsNkeyFile(seed).build())) {
                assertEquals(List.of("seeded"), member.getMembers());
            }
        }
    }

    /** Runs openssl in the test's folder; skips the test without it (fails under DTRON_REQUIRE_TOOLS=1). */
    private void openssl(String... args) throws Exception {
        List<String> command = new ArrayList<>(List.of("openssl"));
        command.addAll(List.of(args));
        boolean ran;
        Process process = null;
        try {
            process = new ProcessBuilder(command).directory(dir.toFile()).redirectErrorStream(true)
                    .redirectOutput(dir.resolve("openssl.log").toFile()).start();
            ran = process.waitFor(60, TimeUnit.SECONDS) && process.exitValue() == 0;
        } catch (java.io.IOException e) {
            ran = false;
        }
        NatsServer.requireTool(ran || process != null, "openssl");
        assertTrue(ran, "openssl " + String.join(" ", args) + ":\n" + Files.readString(dir.resolve("openssl.log")));
    }

    @Test
    void tlsToTheServersTrustsTheGivenAuthorityOnly() throws Exception {
        openssl("req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", "ca.key", "-out", "ca.pem", "-days", "1",
                "-subj", "/CN=dtron-test-ca");
        openssl("req", "-newkey", "rsa:2048", "-nodes", "-keyout", "server.key", "-out", "server.csr", "-subj",
                "/CN=127.0.0.1");
        Files.writeString(dir.resolve("san.cnf"), "subjectAltName=IP:127.0.0.1\n");
        openssl("x509", "-req", "-in", "server.csr", "-CA", "ca.pem", "-CAkey", "ca.key", "-CAcreateserial", "-out",
                "server.pem", "-days", "1", "-extfile", "san.cnf");
        try (NatsServer server = NatsServer.startWith(dir, List.of("--tls", "--tlscert",
                dir.resolve("server.pem").toString(), "--tlskey", dir.resolve("server.key").toString()))) {
            String cluster = TestClusters.uniqueName("tls");
            String url = server.url().replace("nats://", "tls://");
            org.junit.jupiter.api.Assertions.assertThrows(DtronException.class, () -> Dtron.connect(
                    DtronOptions.builder().clusterName(cluster).memberName("untrusting").natsServers(url).build()));
            try (Dtron member = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("trusting")
                    .natsServers(url).natsTlsCaFile(dir.resolve("ca.pem")).build())) {
                Inbox inbox = new Inbox(ORDER);
                member.addDtronListener(inbox);
                member.send(ORDER.constructValued(Map.of("n", 1)));
                assertEquals(1, inbox.take().getVariables().get("n"), "a message over TLS");
            }
        }
    }

    @Test
    void badInputIsRejectedAndCounted() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            String cluster = TestClusters.uniqueName("bad");
            try (Dtron tester = Dtron.connect(nats(server, cluster, "tester").secret(NatsSecurityTest.SECRET)
                    .channels(List.of(ORDER)).build());
                    io.nats.client.Connection raw = io.nats.client.Nats.connect(server.url())) {
                Inbox inbox = new Inbox(ORDER);
                tester.addDtronListener(inbox);
                // a client with the bus's secret, publishing by hand
                io.nats.client.JetStream js = raw.jetStream();
                NatsSecurityTest.publishSigned(js, "dtron." + cluster + ".c.order", "raw", 1,
                        new byte[] {(byte) 0xFF, 1, 2});
                NatsSecurityTest.publishSigned(js, "dtron." + cluster + ".c.nosuch", "raw", 2,
                        io.dtron.api.internal.SyncCodec.encode("nosuch", Map.of(), "raw", 1, 1));
                NatsSecurityTest.publishSigned(js, "dtron." + cluster + ".c.order", "raw", 3,
                        io.dtron.api.internal.SyncCodec.encode("order", Map.of("n", 1, "m", 2), "raw", 2, 1));
                NatsSecurityTest.publishSigned(js, "dtron." + cluster + ".c.order", "raw", 4,
                        io.dtron.api.internal.SyncCodec.encode("order", Map.of("n", 7), "raw", 3, 1));
                IDtronChannelValued good = inbox.take();
                assertEquals(7, good.getVariables().get("n"));
                assertEquals("raw", good.getSender());
                DtronStats stats = tester.getStats();
                assertEquals(3, stats.getRejectedTotal(), stats.toString());
                assertEquals(1, stats.getRejected(InvalidMessageException.Reason.MALFORMED), stats.toString());
                assertEquals(1, stats.getRejected(InvalidMessageException.Reason.UNKNOWN_CHANNEL), stats.toString());
                assertEquals(1, stats.getAccepted(), stats.toString());
            }
        }
    }

    /**
     * The server loses a member's consumer (as when the server that held it dies): the member notices (the NATS
     * client by its missed heartbeats, else the transport's own watchdog) and makes its consumer anew from the next
     * message it has not delivered, so that nothing published meanwhile is lost.
     */
    @Test
    void aMemberWhoseConsumerIsDeletedOnTheServerStillReceivesEveryMessageInOrder() throws Exception {
        try (NatsServer server = NatsServer.start(dir)) {
            String cluster = TestClusters.uniqueName("consumer");
            Inbox inboxB = new Inbox(ORDER);
            try (Dtron a = Dtron.connect(nats(server, cluster, "a").build());
                    Dtron b = Dtron.connect(nats(server, cluster, "b").build())) {
                b.addDtronListener(inboxB);
                assertTrue(b.awaitMembers(2, Duration.ofSeconds(10)), "b sees a: " + b.getMembers());
                a.send(ORDER.constructValued(Map.of("n", 1)));
                assertEquals(1, inboxB.take().getVariables().get("n"));
                try (io.nats.client.Connection admin = io.nats.client.Nats.connect(server.url())) {
                    io.nats.client.JetStreamManagement management = admin.jetStreamManagement();
                    for (String consumer : management.getConsumerNames("DTRON_" + cluster)) {
                        management.deleteConsumer("DTRON_" + cluster, consumer);
                    }
                }
                for (int n = 2; n <= 50; n++) {
                    a.send(ORDER.constructValued(Map.of("n", n)));
                }
                for (int n = 2; n <= 50; n++) {
                    IDtronChannelValued got = inboxB.poll(20_000);
                    assertTrue(got != null, "message " + n + " never came");
                    assertEquals(n, got.getVariables().get("n"), "in order, none lost or twice");
                }
            }
        }
    }
}
