package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Inbox;
import java.time.Duration;
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
