package io.dtron.api;

import io.dtron.api.internal.TestHooks;
import io.dtron.api.internal.TesterSide;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.internal.BusConnector;
import io.dtron.api.internal.SyncCodec;
import io.dtron.api.internal.proto.Sync;
import io.dtron.bus.internal.Transport;
import io.dtron.testsupport.Inbox;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** Event times, run ids and clock offsets travel with every message; reserved channel names are refused. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class EventTimeTest {
    private static final IDtronChannel DONE = IDtronChannel.of("done", "amount");
    private final String cluster = TestClusters.uniqueName("eventTime");

    @Test
    void aMessageHappenedWhenPublishedUnlessTheSenderSaysWhen() throws Exception {
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").build());
                Dtron adapter = Dtron.connect(TestClusters.inJvm(cluster).memberName("adapter").build())) {
            assertTrue(tester.awaitMembers(2, Duration.ofSeconds(10)));
            Inbox dones = new Inbox(DONE);
            tester.addDtronListener(dones);

            IDtronChannelValued sent = adapter.send(DONE.constructValued(Map.of("amount", 1)));
            IDtronChannelValued now = dones.take();
            assertEquals(List.of("adapter", now.getSequence(), now.getPublishTimeNanos(), now.getEventTimeNanos(),
                    now.getVariables(), 0L), List.of(sent.getSender(), sent.getSequence(), sent.getPublishTimeNanos(),
                    sent.getEventTimeNanos(), sent.getVariables(), sent.getReceiveTimeNanos()),
                    "send returns the message as published");
            assertTrue(now.getPublishTimeNanos() > 0);
            assertEquals(now.getPublishTimeNanos(), now.getEventTimeNanos());
            assertEquals(0, now.getClockOffsetNanos(), "no tester known, no estimate");
            assertEquals(0, now.getClockErrorNanos());
            assertEquals("", now.getRunId());
            assertEquals("", now.getAckedSender());
            assertEquals(0, now.getAckedSequence());

            long sawIt = adapter.currentTimeNanos() - 5_000_000;
            assertEquals(sawIt, adapter.send(DONE.constructValued(Map.of("amount", 2)), sawIt).getEventTimeNanos());
            IDtronChannelValued earlier = dones.take();
            assertEquals(sawIt, earlier.getEventTimeNanos());
            assertTrue(earlier.getPublishTimeNanos() >= sawIt + 5_000_000);
            assertThrows(IllegalArgumentException.class, () -> adapter.send(DONE.constructValued(Map.of("amount",
                    3)), 0));

            // the bytes keep all of it
            IDtronChannelValued decoded = DONE.constructValued(earlier.toByteArray());
            assertEquals(sawIt, decoded.getEventTimeNanos());
            assertEquals(earlier.getPublishTimeNanos(), decoded.getPublishTimeNanos());
            assertEquals("adapter", decoded.getSender());
            assertEquals(0, Sync.parseFrom(now.toByteArray()).getEventTimeNs(),
                    "an event time equal to the publish time is left out of the bytes");
        }
    }

    @Test
    void aMessageOfAnOldSenderHappenedWhenPublished() throws Exception {
        try (Dtron member = Dtron.connect(TestClusters.inJvm(cluster).build());
                Transport old = BusConnector.connect(TestClusters.inJvm(cluster).memberName("old").build())) {
            assertTrue(member.awaitMembers(2, Duration.ofSeconds(10)));
            Inbox dones = new Inbox(DONE);
            member.addDtronListener(dones);
            old.publish("done", SyncCodec.encode("done", Map.of("amount", 7), "old", 1, 123_456_789L));
            IDtronChannelValued message = dones.take();
            assertEquals(123_456_789L, message.getEventTimeNanos());
            assertEquals(0, message.getClockErrorNanos());
            assertEquals("", message.getRunId());
        }
    }

    @Test
    void theRunIdOfTheTesterTravelsWithTheRunsMessages() throws Exception {
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
                Dtron adapter = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("adapter"),
                        Duration.ofMillis(-40)).build())) {
            ClockOffsetTest.awaitOffset(adapter);
            Inbox starts = new Inbox(Dtron.RUN_START);
            Inbox stops = new Inbox(Dtron.RUN_STOP);
            Inbox dones = new Inbox(DONE);
            adapter.addDtronListener(starts);
            adapter.addDtronListener(stops);
            tester.addDtronListener(dones);

            TesterSide.of(tester).setRunId("run-42");
            assertEquals("run-42", tester.getRunId());
            tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 1_000)));
            IDtronChannelValued start = starts.take();
            assertEquals("run-42", start.getRunId());
            assertEquals(0, start.getClockOffsetNanos(), "the tester's messages carry no offset");
            assertEquals(0, start.getClockErrorNanos());
            assertEquals("run-42", adapter.getRunId(), "a member takes the run id from RUN_START");

            adapter.send(DONE.constructValued(Map.of("amount", 1)));
            IDtronChannelValued done = dones.take();
            assertEquals("run-42", done.getRunId());
            assertTrue(done.getClockErrorNanos() > 0, "a member's messages carry its offset estimate");
            assertTrue(Math.abs(done.getClockOffsetNanos() - 40_000_000) <= done.getClockErrorNanos(),
                    done.getClockOffsetNanos() + " +/- " + done.getClockErrorNanos());

            tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
            assertEquals("run-42", stops.take().getRunId());
            adapter.send(DONE.constructValued(Map.of("amount", 2)));
            assertEquals("", dones.take().getRunId(), "between runs, no run id");
            TesterSide.of(adapter).setRunId("mine");
            adapter.send(DONE.constructValued(Map.of("amount", 3)));
            assertEquals("mine", dones.take().getRunId());
        }
    }

    @Test
    void reservedChannelNamesAreRefusedForModelChannels() {
        for (String name : List.of("dtron_start", "dtron_stop", "dtron_ack", "dtron_hello", "dtron_ping",
                "dtron_pong", "dtron_model", "dtron_model_outcome")) {
            assertTrue(Dtron.isReservedChannel(name), name);
        }
        assertTrue(!Dtron.isReservedChannel("move") && !Dtron.isReservedChannel("dtron_other"));
        DtronOptions.Builder options = DtronOptions.builder();
        options.channels(List.of(DONE, Dtron.RUN_START, Dtron.RUN_STOP));
        assertThrows(IllegalArgumentException.class, () -> options.channels(List.of(Dtron.ACK)));
        assertThrows(IllegalArgumentException.class,
                () -> options.channels(List.of(IDtronChannel.of("dtron_ack", "amount"))));
        assertThrows(IllegalArgumentException.class,
                () -> options.channels(List.of(IDtronChannel.of("dtron_stop", "amount"))));
        assertThrows(IllegalArgumentException.class, () -> options.channels(List.of(IDtronChannel.of("dtron_ping"))));
        assertThrows(IllegalArgumentException.class, () -> options.channels(List.of(Dtron.MODEL_VERSION)));
        try (Dtron member = Dtron.connect(TestClusters.inJvm(cluster).build())) {
            assertThrows(IllegalArgumentException.class,
                    () -> member.addDtronListener(new Inbox(IDtronChannel.of("dtron_ack", "amount"))));
            assertThrows(IllegalArgumentException.class,
                    () -> member.addDtronListener(new Inbox(IDtronChannel.of("dtron_start"))));
            assertThrows(IllegalArgumentException.class,
                    () -> member.addDtronListener(new Inbox(IDtronChannel.of("dtron_pong"))));
            assertThrows(IllegalArgumentException.class,
                    () -> member.send(IDtronChannel.of("dtron_hello").constructValued(Map.of())));
            assertThrows(IllegalArgumentException.class, () -> member.send(Dtron.ACK.constructValued(Map.of())));
            assertThrows(InvalidMessageException.class,
                    () -> member.send(IDtronChannel.of("dtron_stop", "x").constructValued(Map.of("x", 1))));
            member.addDtronListener(new Inbox(Dtron.ACK));
            assertNotEquals(null, member.runClock());
        }
    }
}
