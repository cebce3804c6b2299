package io.dtron.bus.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.bus.internal.BusMessage;
import io.dtron.bus.internal.MembershipView;
import io.dtron.bus.internal.Subscription;
import io.dtron.testsupport.Waits;
import java.net.InetAddress;
import java.util.List;
import java.util.Optional;
import java.util.UUID;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** The transport on its own, in one JVM without sockets. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class JGroupsTransportTest {
    private final String cluster = "transport-" + UUID.randomUUID();

    private JGroupsTransport connect(String member) throws Exception {
        return JGroupsTransport.connect(new JGroupsSettings(cluster, member, InetAddress.getLoopbackAddress(), 7800,
                30, List.of(), Optional.empty(), false, true));
    }

    private static BusMessage take(BlockingQueue<BusMessage> queue) throws InterruptedException {
        BusMessage message = queue.poll(10, TimeUnit.SECONDS);
        assertNotNull(message, "no message within 10 s");
        return message;
    }

    @Test
    void groupSubscribersGetTheirGroupOnlyAndAllSubscribersEverything() throws Exception {
        try (JGroupsTransport a = connect("a"); JGroupsTransport b = connect("b")) {
            BlockingQueue<BusMessage> moves = new LinkedBlockingQueue<>();
            BlockingQueue<BusMessage> all = new LinkedBlockingQueue<>();
            b.subscribe("move", moves::add);
            b.subscribeAll(all::add);
            awaitMembers(b, 2);

            long before = EpochClock.nowNanos();
            a.publish("done", new byte[] {1});
            a.publish("move", new byte[] {2});

            BusMessage move = take(moves);
            assertEquals("move", move.group());
            assertArrayEquals(new byte[] {2}, move.payload());
            assertEquals("a", move.sender());
            assertTrue(move.receiveTimeNanos() >= before);
            assertEquals(List.of("done", "move"), List.of(take(all).group(), take(all).group()));
            assertNull(moves.poll(100, TimeUnit.MILLISECONDS));
        }
    }

    @Test
    void closedSubscriptionStopsAndAFailingHandlerDoesNotStopOthers() throws Exception {
        try (JGroupsTransport a = connect("a")) {
            BlockingQueue<BusMessage> received = new LinkedBlockingQueue<>();
            BlockingQueue<BusMessage> stopped = new LinkedBlockingQueue<>();
            a.subscribe("move", m -> {
                throw new IllegalStateException("handler bug");
            });
            a.subscribe("move", received::add);
            Subscription subscription = a.subscribe("move", stopped::add);

            a.publish("move", new byte[] {1});
            take(received);
            take(stopped);
            subscription.close();
            subscription.close();
            a.publish("move", new byte[] {2});
            assertArrayEquals(new byte[] {2}, take(received).payload());
            assertNull(stopped.poll(100, TimeUnit.MILLISECONDS));
        }
    }

    @Test
    void viewsTellWhoJoinedAndLeft() throws Exception {
        try (JGroupsTransport a = connect("a")) {
            BlockingQueue<MembershipView> views = new LinkedBlockingQueue<>();
            a.addViewListener(views::add);
            MembershipView alone = a.view();
            assertEquals(List.of("a"), alone.members());

            MembershipView joined;
            try (JGroupsTransport b = connect("b")) {
                joined = views.poll(10, TimeUnit.SECONDS);
                assertNotNull(joined);
                assertEquals(List.of(b.localMember()), joined.joinedSince(alone));
                assertTrue(joined.id() > alone.id());
            }
            MembershipView left = views.poll(10, TimeUnit.SECONDS);
            assertNotNull(left);
            assertEquals(List.of("b"), left.leftSince(joined));
            assertEquals(List.of("a"), left.members());
        }
    }

    @Test
    void publishingAfterCloseFails() throws Exception {
        JGroupsTransport a = connect("a");
        a.close();
        a.close();
        assertThrows(IllegalStateException.class, () -> a.publish("move", new byte[0]));
    }

    private static void awaitMembers(JGroupsTransport transport, int count) {
        Waits.await(count + " members").until(() -> transport.view().members().size(), c -> c == count);
    }
}
