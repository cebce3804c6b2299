package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import ch.qos.logback.classic.Level;
import ch.qos.logback.classic.spi.ILoggingEvent;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.LogCapture;
import io.dtron.testsupport.Waits;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** Members in one JVM over the in-memory transport: the whole API without sockets. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class DtronInJvmTest {
    private static final Duration WAIT = Duration.ofSeconds(10);
    private final IDtronChannel move = IDtronChannel.of("move", "amount");
    private final IDtronChannel done = IDtronChannel.of("done", "amount");
    private final String cluster = TestClusters.uniqueName("inJvm");

    @Test
    void membersExchangeMessagesWithSenderSequenceAndTimes() throws Exception {
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").build());
                Dtron adapter = Dtron.connect(TestClusters.inJvm(cluster).memberName("adapter").build())) {
            assertTrue(tester.awaitMembers(2, WAIT));
            assertEquals(List.of("tester", "adapter"), adapter.getMembers());
            Inbox inbox = new Inbox(move);
            adapter.addDtronListener(inbox);

            long before = System.currentTimeMillis() * 1_000_000L;
            tester.send(move.constructValued(Map.of("amount", 7)));
            tester.send(move.constructValued(Map.of("amount", -2)));

            IDtronChannelValued first = inbox.take();
            assertEquals(Map.of("amount", 7), first.getVariables());
            assertEquals("tester", first.getSender());
            // the sender's own messages of DTRON (its handshake when it first sends on a channel) take numbers too
            assertTrue(first.getSequence() >= 1 && first.getSequence() <= 2, "sequence " + first.getSequence());
            assertTrue(first.getPublishTimeNanos() >= before - 1_000_000, "publish time is epoch nanos");
            assertTrue(first.getReceiveTimeNanos() >= first.getPublishTimeNanos(), "received after published");
            IDtronChannelValued second = inbox.take();
            assertEquals(-2, second.getVariables().get("amount"));
            assertTrue(second.getSequence() > first.getSequence(), "sequence " + second.getSequence());
            assertEquals(2, tester.getStats().getPublished());
            assertEquals(2, adapter.getStats().getAccepted());
        }
    }

    @Test
    void aModelVersionAndItsOutcomeCarryTheirTextOnlyOnDtronsChannelsOfText() throws Exception {
        try (Dtron controller = Dtron.connect(TestClusters.inJvm(cluster).build());
                Dtron sender = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            assertTrue(controller.awaitMembers(2, WAIT));
            Inbox versions = new Inbox(Dtron.MODEL_VERSION);
            controller.addDtronListener(versions);
            Inbox outcomes = new Inbox(Dtron.MODEL_OUTCOME);
            sender.addDtronListener(outcomes);
            String version = "{\"model\": \"chan i_move; // \u00e9t\u00e9\\n\"}";
            IDtronChannelValued sent = sender.send(Dtron.MODEL_VERSION.constructValued(Map.of("version", 3)), version);
            assertEquals(version, sent.getText());
            IDtronChannelValued received = versions.take();
            assertEquals(version, received.getText());
            assertEquals(Map.of("version", 3), received.getVariables());
            controller.send(Dtron.MODEL_OUTCOME.constructValued(Map.of("version", 3, "outcome", 2)), "refused: why");
            IDtronChannelValued outcome = outcomes.take();
            assertEquals("refused: why", outcome.getText());
            assertEquals(Map.of("version", 3, "outcome", 2), outcome.getVariables());

            Inbox moves = new Inbox(move);
            controller.addDtronListener(moves);
            assertThrows(IllegalArgumentException.class,
                    () -> sender.send(move.constructValued(Map.of("amount", 1)), "text"));
            sender.send(move.constructValued(Map.of("amount", 1)));
            assertEquals("", moves.take().getText());
        }
    }

    @Test
    void listenerRepliesInlineAndSeesItsOwnMessagesInOrder() throws Exception {
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).build());
                Dtron adapter = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            assertTrue(tester.awaitMembers(2, WAIT));
            adapter.addDtronListener(new DtronListener(move) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    int amount = message.getVariables().get("amount");
                    getDtron().send(done.constructValued(Map.of("amount", amount * 2)));
                }
            });
            Inbox testerDone = new Inbox(done);
            Inbox adapterDone = new Inbox(done);
            tester.addDtronListener(testerDone);
            adapter.addDtronListener(adapterDone);

            for (int i = 1; i <= 20; i++) {
                tester.send(move.constructValued(Map.of("amount", i)));
            }
            for (int i = 1; i <= 20; i++) {
                IDtronChannelValued reply = testerDone.take();
                assertEquals(2 * i, reply.getVariables().get("amount"));
                assertEquals(adapter.getMemberId(), reply.getSender());
                IDtronChannelValued own = adapterDone.take();
                assertEquals(List.of(reply.getVariables(), reply.getSender(), reply.getSequence(),
                        reply.getPublishTimeNanos()), List.of(own.getVariables(), own.getSender(), own.getSequence(),
                        own.getPublishTimeNanos()), "the sender receives its own message in the same order");
            }
        }
    }

    @Test
    void throwingListenerIsLoggedWithTheMessageAndKeepsReceiving() throws Exception {
        try (LogCapture log = new LogCapture(Dtron.class);
                Dtron dtron = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            Inbox inbox = new Inbox(move);
            dtron.addDtronListener(new DtronListener(move) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    if (message.getVariables().get("amount") == 13) {
                        throw new IllegalStateException("unlucky");
                    }
                    inbox.messageReceived(message);
                }
            });
            dtron.send(move.constructValued(Map.of("amount", 13)));
            dtron.send(move.constructValued(Map.of("amount", 14)));

            assertEquals(14, inbox.take().getVariables().get("amount"));
            assertEquals(1, dtron.getStats().getListenerFailures());
            List<ILoggingEvent> errors = log.events(Level.ERROR);
            assertEquals(1, errors.size());
            assertTrue(errors.get(0).getFormattedMessage().contains("move{amount=13}"),
                    errors.get(0).getFormattedMessage());
            assertEquals("unlucky", errors.get(0).getThrowableProxy().getMessage());
        }
    }

    @Test
    void removedListenerReceivesNoMore() throws Exception {
        try (Dtron dtron = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            Inbox removed = new Inbox(move);
            Inbox kept = new Inbox(move);
            dtron.addDtronListener(removed);
            dtron.addDtronListener(kept);
            dtron.send(move.constructValued(Map.of("amount", 1)));
            assertEquals(1, removed.take().getVariables().get("amount"));
            assertEquals(1, kept.take().getVariables().get("amount"));

            dtron.removeDtronListener(removed);
            assertThrows(IllegalStateException.class, removed::getDtron);
            dtron.send(move.constructValued(Map.of("amount", 2)));
            assertEquals(2, kept.take().getVariables().get("amount"));
            assertNull(removed.poll(200));
        }
    }

    @Test
    void listenerTemplateMustMatchTheChannel() {
        try (Dtron dtron = Dtron.connect(TestClusters.inJvm(cluster).build());
                Dtron other = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            Inbox inbox = new Inbox(move);
            dtron.addDtronListener(inbox);
            assertThrows(IllegalArgumentException.class,
                    () -> dtron.addDtronListener(new Inbox(IDtronChannel.of("move", "speed"))));
            assertThrows(IllegalStateException.class, () -> other.addDtronListener(inbox));
            assertThrows(InvalidMessageException.class,
                    () -> dtron.send(IDtronChannel.of("move", "speed").constructValued(Map.of("speed", 1))));
        }
    }

    @Test
    void membershipViewsTellWhoJoinedAndLeft() throws Exception {
        try (Dtron first = Dtron.connect(TestClusters.inJvm(cluster).memberName("first").build())) {
            assertEquals(List.of("first"), first.getMembers());
            try (Dtron second = Dtron.connect(TestClusters.inJvm(cluster).memberName("second").build())) {
                assertTrue(first.awaitMembers(2, WAIT));
                assertEquals(List.of("first", second.getMemberId()), first.getMembers());
            }
            Waits.await("the second member gone").until(first::getMembers, List.of("first")::equals);
            assertFalse(first.awaitMembers(2, Duration.ofMillis(100)));
        }
    }

    @Test
    void closedDtronRefusesToSend() {
        Dtron dtron = Dtron.connect(TestClusters.inJvm(cluster).build());
        dtron.close();
        dtron.close();
        assertThrows(IllegalStateException.class, () -> dtron.send(move.constructValued(Map.of("amount", 1))));
    }
}
