package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.LogCapture;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import org.jgroups.protocols.SYM_ENCRYPT;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * Members over TCP on loopback on free ports, found without configuration: with the default key file, a secret given,
 * encrypted, insecure; members with another secret, or none, never hear each other.
 */
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
    void insecureMembersExchangeMessages() throws Exception {
        assertExchange(options().insecure(true).build(), options().insecure(true).build());
    }

    @Test
    void aMemberWithAnotherSecretIsNeverSeenAndNeverHeard() throws Exception {
        assertStrangerUnseen(options().secret("guess").build());
    }

    @Test
    void anInsecureMemberIsNeverSeenByASecureOne() throws Exception {
        assertStrangerUnseen(options().insecure(true).build());
    }

    /** With encryption, a stranger that started first used to make every member log errors about its messages. */
    @Test
    void encryptedMembersLogNothingAboutAStrangerWithAnotherSecret() throws Exception {
        try (LogCapture encryption = new LogCapture(SYM_ENCRYPT.class)) {
            assertStrangerUnseen(options().secret("guess").encrypt(true).build(), true);
            assertEquals(List.of(), encryption.messages());
        }
    }

    private void assertStrangerUnseen(DtronOptions strangerOptions) throws Exception {
        assertStrangerUnseen(strangerOptions, false);
    }

    /** The stranger joins first and speaks; two members with the secret see only each other and hear only each other. */
    private void assertStrangerUnseen(DtronOptions strangerOptions, boolean encrypt) throws Exception {
        List<List<String>> views = new CopyOnWriteArrayList<>();
        try (Dtron stranger = Dtron.connect(strangerOptions);
                Dtron a = Dtron.connect(options().secret("s3cret").encrypt(encrypt).build())) {
            a.addMembershipListener((members, joined, left) -> views.add(members));
            views.add(a.getMembers());
            try (Dtron b = Dtron.connect(options().secret("s3cret").encrypt(encrypt).build())) {
                assertTrue(a.awaitMembers(2, WAIT), () -> "members: " + a.getMembers());
                Inbox inbox = new Inbox(move);
                b.addDtronListener(inbox);
                stranger.send(move.constructValued(Map.of("amount", 9)));
                a.send(move.constructValued(Map.of("amount", 5)));
                IDtronChannelValued received = inbox.take();
                assertEquals(a.getMemberId(), received.getSender(), "only a member with the secret is heard");
                assertEquals(5, received.getVariables().get("amount"));
                assertEquals(Set.of(a.getMemberId(), b.getMemberId()), Set.copyOf(b.getMembers()));
                assertEquals(List.of(stranger.getMemberId()), stranger.getMembers());
                assertTrue(views.stream().noneMatch(v -> v.contains(stranger.getMemberId())), views::toString);
            }
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
