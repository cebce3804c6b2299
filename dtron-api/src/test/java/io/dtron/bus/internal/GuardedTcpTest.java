package io.dtron.bus.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import ch.qos.logback.classic.Level;
import io.dtron.bus.BusMessage;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.LogCapture;
import io.dtron.testsupport.Waits;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.net.InetAddress;
import java.net.Socket;
import java.net.SocketException;
import java.util.Arrays;
import java.util.List;
import java.util.Optional;
import java.util.Random;
import java.util.UUID;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * Members over TCP with the guard: a member with another secret is never in a view nor heard, even when it holds the
 * first bus port; frames announcing huge lengths or carrying no valid code end their connection, unparsed, with one
 * line in the log for the host and no stack trace.
 */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class GuardedTcpTest {
    private static final InetAddress LOOPBACK = InetAddress.getLoopbackAddress();
    private final String cluster = "guard-" + UUID.randomUUID().toString().substring(0, 8);
    private final int port = FreePorts.range(FreePorts.BUS_RANGE);

    private JGroupsTransport member(String name, Optional<String> secret) throws Exception {
        return JGroupsTransport.connect(new JGroupsSettings(cluster, name, LOOPBACK, port, FreePorts.BUS_RANGE,
                List.of(), secret, false, false));
    }

    @Test
    void aSquatterWithAnotherSecretOnTheFirstPortIsNeverSeenNorHeard() throws Exception {
        try (JGroupsTransport squatter = member("squatter", Optional.of("guess"));
                JGroupsTransport a = member("a", Optional.of("s3cret"));
                JGroupsTransport b = member("b", Optional.of("s3cret"))) {
            Waits.await("a and b see each other").until(() -> a.view().members().size() == 2
                    && b.view().members().size() == 2);
            assertEquals(List.of("a", "b"), a.view().members(), "the squatter never is a member, nor coordinator");
            assertEquals(List.of("squatter"), squatter.view().members());
            BlockingQueue<BusMessage> heard = new LinkedBlockingQueue<>();
            b.subscribe("move", heard::add);
            squatter.publish("move", new byte[] {9});
            a.publish("move", new byte[] {5});
            BusMessage first = heard.poll(Waits.TIMEOUT.toSeconds(), TimeUnit.SECONDS);
            assertEquals("a", first.sender(), "only a member with the secret is heard");
            assertTrue(squatter.rejectedFrames() > 0, "the squatter dropped the discovery of a and b");
        }
    }

    @Test
    void insecureAndSecureMembersDoNotHearEachOther() throws Exception {
        try (JGroupsTransport insecure = member("insecure", Optional.empty());
                JGroupsTransport secure = member("secure", Optional.of("s3cret"));
                JGroupsTransport insecure2 = member("insecure2", Optional.empty())) {
            Waits.await("the insecure members see each other").until(() -> insecure.view().members().size() == 2);
            assertEquals(List.of("insecure", "insecure2"), insecure.view().members());
            assertEquals(List.of("secure"), secure.view().members());
        }
    }

    @Test
    void framesOfHugeLengthsOrWithoutCodesEndTheirConnectionWithOneLineAndNoStackTrace() throws Exception {
        try (LogCapture log = new LogCapture(GuardedTcp.class);
                JGroupsTransport a = member("a", Optional.of("s3cret"))) {
            long heapBefore = usedHeap();
            for (int i = 0; i < 5; i++) {
                try (Socket socket = new Socket(LOOPBACK, port)) {
                    DataOutputStream out = new DataOutputStream(socket.getOutputStream());
                    out.writeInt(Integer.MAX_VALUE); // the announced length
                    out.write(new byte[74]);
                    out.flush();
                    assertClosedByPeer(socket);
                }
            }
            assertTrue(usedHeap() - heapBefore < 256L * 1024 * 1024, "nothing was allocated for 2 GB frames");
            byte[] garbage = new byte[64 * 1024];
            new Random(7).nextBytes(garbage);
            garbage[0] = 0; // a plausible length, 0x000010xx: read in full, and found without a code
            garbage[1] = 0;
            garbage[2] = 0x10;
            try (Socket socket = new Socket(LOOPBACK, port)) {
                socket.getOutputStream().write(garbage);
                assertClosedByPeer(socket);
            }
            assertEquals(6, a.rejectedFrames());
            List<String> warnings = log.events(Level.WARN).stream().map(e -> e.getFormattedMessage()).toList();
            assertEquals(1, warnings.size(), warnings::toString);
            assertTrue(warnings.get(0).contains("2147483647"), warnings.get(0));
            assertFalse(log.anyStackTrace());
            assertEquals(List.of("a"), a.view().members());
        }
    }

    /** The member closed the connection, saying nothing but JGroups' graceful close (a length of -5) first. */
    private static void assertClosedByPeer(Socket socket) throws IOException {
        socket.setSoTimeout((int) Waits.TIMEOUT.toMillis());
        InputStream in = socket.getInputStream();
        try {
            byte[] said = in.readAllBytes();
            assertTrue(said.length == 0 || Arrays.equals(new byte[] {-1, -1, -1, -5}, said), Arrays.toString(said));
        } catch (SocketException e) {
            // a reset: closed too, with bytes of ours unread
        }
    }

    private static long usedHeap() {
        Runtime runtime = Runtime.getRuntime();
        return runtime.totalMemory() - runtime.freeMemory();
    }
}
