package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Inbox;
import java.net.BindException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** Members over TCP on loopback on free ports, found without configuration; with and without a secret, encrypted. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class TcpBusTest {
    private static final Duration WAIT = Duration.ofSeconds(15);
    private final IDtronChannel move = IDtronChannel.of("move", "amount");
    private final String cluster = TestClusters.uniqueName("tcp");
    private final int port = FreePorts.range(FreePorts.BUS_RANGE);

    private DtronOptions.Builder options() {
        return DtronOptions.builder().clusterName(cluster).port(port).portRange(FreePorts.BUS_RANGE);
    }

    @Test
    void membersFindEachOtherOnLoopbackWithoutConfiguration() throws Exception {
        assertExchange(options().build(), options().build());
    }

    @Test
    void membersWithTheSameSecretJoin() throws Exception {
        assertExchange(options().secret("s3cret").build(), options().secret("s3cret").build());
    }

    @Test
    void encryptedMembersExchangeMessages() throws Exception {
        assertExchange(options().secret("s3cret").encrypt(true).build(),
                options().secret("s3cret").encrypt(true).build());
    }

    @Test
    void memberWithAWrongSecretIsRefused() {
        try (Dtron first = Dtron.connect(options().secret("s3cret").build())) {
            DtronException refused = assertThrows(DtronException.class,
                    () -> Dtron.connect(options().secret("guess").build()).close());
            assertTrue(refused.getMessage().contains("refused"), refused.getMessage());
            assertEquals(1, first.getMembers().size());
        }
    }

    /**
     * The failure detector's server socket (FD_SOCK2, 100 above the member's port) listens at the bind address, not
     * on every interface: the same port at another loopback address is free, at the bind address it is taken.
     */
    @Test
    void theFailureDetectorListensAtTheBindAddressOnly() throws Exception {
        int port;
        try (ServerSocket free = new ServerSocket(0, 1, InetAddress.getByName("127.0.0.1"))) {
            port = free.getLocalPort();
        }
        InetAddress bind = InetAddress.getByName("127.0.0.1");
        try (Dtron member = Dtron.connect(options().bindAddress(bind).port(port).portRange(0)
                .initialMembers(List.of(new InetSocketAddress(bind, port))).build())) {
            assertEquals(1, member.getMembers().size());
            try (ServerSocket elsewhere = new ServerSocket(port + 100, 1, InetAddress.getByName("127.0.0.2"))) {
                assertEquals(port + 100, elsewhere.getLocalPort());
            }
            assertThrows(BindException.class, () -> new ServerSocket(port + 100, 1, bind).close(),
                    "the failure detector listens at " + bind + ":" + (port + 100));
        }
    }

    private void assertExchange(DtronOptions first, DtronOptions second) throws Exception {
        try (Dtron a = Dtron.connect(first); Dtron b = Dtron.connect(second)) {
            assertTrue(a.awaitMembers(2, WAIT), () -> "members: " + a.getMembers());
            Inbox inbox = new Inbox(move);
            b.addDtronListener(inbox);
            a.send(move.constructValued(Map.of("amount", 5)));
            IDtronChannelValued received = inbox.take();
            assertEquals(5, received.getVariables().get("amount"));
            assertEquals(a.getMemberId(), received.getSender());
        }
    }
}
