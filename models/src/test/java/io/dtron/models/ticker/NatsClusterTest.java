package io.dtron.models.ticker;

import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.Waits;
import io.nats.client.Connection;
import io.nats.client.JetStreamApiException;
import io.nats.client.JetStreamManagement;
import io.nats.client.Nats;
import io.nats.client.api.StorageType;
import io.nats.client.api.StreamConfiguration;
import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.CleanupMode;
import org.junit.jupiter.api.io.TempDir;

/**
 * A cluster of three nats-servers on loopback, the bus's stream replicated on all three: a Java, a Python and a C
 * member, each attached to another server, publish 2,000 messages each; the server of the Python member is killed
 * while they publish. The members that lost their server reconnect to another, and every member records every
 * message once, all in the same order.
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class NatsClusterTest {
    private static final int MESSAGES = 2_000;

    /** Kept when the test fails: the members' logs and records say why. */
    @TempDir(cleanup = CleanupMode.ON_SUCCESS)
    Path dir;

    @Test
    void aServerKilledMidRunLosesNoMessageAndTheOrderHolds() throws Exception {
        int[] ports = {NatsServer.freePort(), NatsServer.freePort(), NatsServer.freePort()};
        int[] routes = {NatsServer.freePort(), NatsServer.freePort(), NatsServer.freePort()};
        List<NatsServer> servers = new ArrayList<>();
        try {
            for (int i = 0; i < 3; i++) {
                List<Integer> others = new ArrayList<>();
                for (int j = 0; j < 3; j++) {
                    if (j != i) {
                        others.add(routes[j]);
                    }
                }
                servers.add(NatsServer.startClustered(dir, "s" + i, ports[i], routes[i], others));
            }
            String bus = NatsTickerTest.cluster("cluster");
            try (Connection admin = Nats.connect(servers.get(0).url())) {
                createReplicatedStream(admin.jetStreamManagement(), bus);
                try (OrderMembers members = new OrderMembers(dir, bus, MESSAGES, servers.get(0).url(),
                        servers.get(1).url(), servers.get(2).url())) {
                    // mid-run: once three quarters of the messages are in the stream
                    Waits.await("three quarters of the messages in the stream").atMost(Duration.ofSeconds(90))
                            .until(() -> messages(admin, bus) >= 3L * MESSAGES / 4);
                    servers.get(1).kill();
                    members.awaitSuccess(Duration.ofSeconds(150), Duration.ofSeconds(60));
                    members.assertOneOrder();
                }
            }
        } finally {
            for (NatsServer server : servers) {
                server.close();
            }
        }
    }

    /** Creates the bus's stream on all three servers, once JetStream's cluster has a leader. */
    private static void createReplicatedStream(JetStreamManagement management, String bus) {
        StreamConfiguration config = StreamConfiguration.builder().name("DTRON_" + bus)
                .subjects("dtron." + bus + ".>").storageType(StorageType.File).replicas(3)
                .maxAge(Duration.ofMinutes(10)).maxBytes(64L * 1024 * 1024).duplicateWindow(Duration.ofMinutes(1))
                .build();
        // refused while JetStream's cluster is still electing its leader
        Waits.await("the replicated stream created").pollInterval(Duration.ofMillis(200))
                .ignoreExceptionsMatching(e -> e instanceof JetStreamApiException || e instanceof IOException)
                .until(() -> management.addStream(config) != null);
    }

    private static long messages(Connection admin, String bus) {
        try {
            return admin.jetStreamManagement().getStreamInfo("DTRON_" + bus).getStreamState().getMsgCount();
        } catch (IOException | JetStreamApiException e) {
            return 0;
        }
    }
}
