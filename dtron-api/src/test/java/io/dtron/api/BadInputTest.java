package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import ch.qos.logback.classic.Level;
import ch.qos.logback.classic.spi.ILoggingEvent;
import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.api.internal.BusConnector;
import io.dtron.api.internal.proto.Sync;
import io.dtron.api.internal.proto.Variable;
import io.dtron.bus.internal.Transport;
import io.dtron.bus.internal.JGroupsTransport;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.LogCapture;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * Bad messages from a raw bus member: each is rejected with a logged reason
 * and counted, and the next valid message is still delivered.
 */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class BadInputTest {
    private final IDtronChannel move = IDtronChannel.of("move", "amount");
    private final String cluster = TestClusters.uniqueName("badInput");
    private Transport injector;
    private LogCapture log;

    @BeforeEach
    void connectInjector() throws Exception {
        DtronOptions options = TestClusters.inJvm(cluster).build();
        injector = JGroupsTransport.connect(BusConnector.settings(options, "injector"));
        log = new LogCapture(Dtron.class);
    }

    @AfterEach
    void close() {
        log.close();
        injector.close();
    }

    @Test
    void bytesThatAreNoSync() throws Exception {
        assertRejected("move", new byte[] {(byte) 0xFF, (byte) 0xFF, 0x07}, Reason.MALFORMED, "not a Sync");
    }

    @Test
    void syncWithoutChannelName() throws Exception {
        assertRejected("move", Sync.newBuilder().addVariables(variable("amount", 1)).build().toByteArray(),
                Reason.MALFORMED, "without a channel name");
    }

    @Test
    void variableTwice() throws Exception {
        assertRejected("move", sync("move", variable("amount", 1), variable("amount", 2)), Reason.MALFORMED,
                "amount appears twice");
    }

    @Test
    void syncNamingAnotherChannelThanItsGroup() throws Exception {
        assertRejected("move", sync("done"), Reason.UNKNOWN_CHANNEL, "names channel 'done'");
    }

    @Test
    void undeclaredChannel() throws Exception {
        DtronOptions strict = TestClusters.inJvm(cluster).channels(List.of(move)).build();
        assertRejected(strict, "bogus", sync("bogus"), Reason.UNKNOWN_CHANNEL, "'bogus' is not declared");
    }

    @Test
    void unknownVariable() throws Exception {
        assertRejected("move", sync("move", variable("amount", 1), variable("colour", 2)), Reason.UNKNOWN_VARIABLES,
                "no variable colour");
    }

    @Test
    void missingVariable() throws Exception {
        assertRejected("move", sync("move"), Reason.MISSING_VARIABLES, "needs variable amount");
    }

    @Test
    void channelsWithoutListenersAreIgnoredUnlessDeclared() throws Exception {
        try (Dtron dtron = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            Inbox inbox = new Inbox(move);
            dtron.addDtronListener(inbox);
            assertTrue(dtron.awaitMembers(2, Duration.ofSeconds(10)));
            injector.publish("other", sync("other"));
            injector.publish("move", sync("move", variable("amount", 3)));
            assertEquals(3, inbox.take().getVariables().get("amount"));
            assertEquals(0, dtron.getStats().getRejectedTotal());
            assertEquals(1, dtron.getStats().getAccepted());
        }
    }

    private void assertRejected(String group, byte[] payload, Reason reason, String logged) throws Exception {
        assertRejected(TestClusters.inJvm(cluster).build(), group, payload, reason, logged);
    }

    private void assertRejected(DtronOptions options, String group, byte[] payload, Reason reason, String logged)
            throws Exception {
        try (Dtron dtron = Dtron.connect(options)) {
            Inbox inbox = new Inbox(move);
            dtron.addDtronListener(inbox);
            assertTrue(dtron.awaitMembers(2, Duration.ofSeconds(10)));

            injector.publish(group, payload);
            injector.publish("move", move.constructValued(Map.of("amount", 42)).toByteArray());

            IDtronChannelValued next = inbox.take();
            assertEquals(42, next.getVariables().get("amount"), "the next valid message is delivered");
            assertEquals("injector", next.getSender(), "a message without a sender field gets the bus sender");
            assertNull(inbox.poll(100), "the bad message is not delivered");
            DtronStats stats = dtron.getStats();
            assertEquals(1, stats.getRejected(reason), stats.toString());
            assertEquals(1, stats.getRejectedTotal(), stats.toString());
            assertEquals(1, stats.getAccepted(), stats.toString());
            List<ILoggingEvent> warnings = log.events(Level.WARN);
            assertEquals(1, warnings.size(), warnings.toString());
            String warning = warnings.get(0).getFormattedMessage();
            assertTrue(warning.contains(reason.name()) && warning.contains(logged) && warning.contains("injector"),
                    warning);
        }
    }

    private static Variable variable(String name, int value) {
        return Variable.newBuilder().setName(name).setValue(value).build();
    }

    private static byte[] sync(String name, Variable... variables) {
        return Sync.newBuilder().setName(name).addAllVariables(List.of(variables)).build().toByteArray();
    }
}
