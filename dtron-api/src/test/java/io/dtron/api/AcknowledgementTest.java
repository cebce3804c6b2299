package io.dtron.api;

import io.dtron.api.internal.TestHooks;
import io.dtron.api.internal.TesterSide;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.Inbox;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** Members acknowledge the inputs of the current run's tester, once each, with the time they applied them. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class AcknowledgementTest {
    private static final IDtronChannel MOVE = IDtronChannel.of("move", "amount");
    private static final IDtronChannel DONE = IDtronChannel.of("done", "amount");
    private static final long APPLYING_MILLIS = 100;
    private final String cluster = TestClusters.uniqueName("ack");
    private Dtron tester;
    private Dtron adapter;
    private Inbox acks;
    private Inbox testerStops;

    @BeforeEach
    void connect() throws InterruptedException {
        // the tester declares its model's channels, as a bridge does: DTRON's own need no declaring
        tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true)
                .channels(List.of(MOVE, DONE, Dtron.RUN_START, Dtron.RUN_STOP)).build());
        adapter = Dtron.connect(TestHooks.clockShift(TestClusters.inJvm(cluster).memberName("adapter"),
                Duration.ofMillis(20)).build());
        assertTrue(tester.awaitMembers(2, Duration.ofSeconds(10)));
        acks = new Inbox(Dtron.ACK);
        tester.addDtronListener(acks);
        testerStops = new Inbox(Dtron.RUN_STOP);
        tester.addDtronListener(testerStops);
    }

    @AfterEach
    void close() {
        adapter.close();
        tester.close();
    }

    private void startRun() throws InterruptedException {
        Inbox starts = new Inbox(Dtron.RUN_START);
        adapter.addDtronListener(starts);
        tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 1_000)));
        starts.take();
        adapter.removeDtronListener(starts);
    }

    /** A listener that takes a while to apply a move and records when it returned. */
    private static final class Applier extends DtronListener {
        final BlockingQueue<IDtronChannelValued> received = new LinkedBlockingQueue<>();
        final BlockingQueue<Long> returnedAt = new LinkedBlockingQueue<>();
        private final boolean automatic;

        Applier(boolean automatic) {
            super(MOVE);
            this.automatic = automatic;
        }

        @Override
        public void messageReceived(IDtronChannelValued message) {
            try {
                Thread.sleep(APPLYING_MILLIS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            received.add(message);
            returnedAt.add(getDtron().currentTimeNanos());
        }

        @Override
        protected boolean autoAcknowledge() {
            return automatic;
        }
    }

    @Test
    void anInputOfTheRunIsAcknowledgedOnceWhenTheLastListenerReturned() throws Exception {
        Applier first = new Applier(true);
        Applier second = new Applier(true);
        adapter.addDtronListener(first);
        adapter.addDtronListener(second);
        Inbox sent = new Inbox(MOVE);
        tester.addDtronListener(sent);

        tester.send(MOVE.constructValued(Map.of("amount", 1)));
        first.received.poll(10, TimeUnit.SECONDS);
        assertNull(acks.poll(300), "no run, no acknowledgement");

        startRun();
        tester.send(MOVE.constructValued(Map.of("amount", 2)));
        sent.take();
        IDtronChannelValued input = sent.take();
        IDtronChannelValued ack = acks.take();
        assertEquals(Dtron.ACK.getChannelName(), ack.getChannelName());
        assertEquals("adapter", ack.getSender());
        assertEquals("tester", ack.getAckedSender());
        assertEquals(input.getSequence(), ack.getAckedSequence());
        assertEquals(Map.of(), ack.getVariables());
        first.returnedAt.poll(10, TimeUnit.SECONDS);
        first.returnedAt.poll(10, TimeUnit.SECONDS);
        second.returnedAt.poll(10, TimeUnit.SECONDS);
        long lastReturned = second.returnedAt.poll(10, TimeUnit.SECONDS);
        first.received.poll(10, TimeUnit.SECONDS);
        second.received.poll(10, TimeUnit.SECONDS);
        IDtronChannelValued applied = second.received.poll(10, TimeUnit.SECONDS);
        assertEquals(2, applied.getVariables().get("amount"));
        assertTrue(ack.getEventTimeNanos() >= lastReturned, "acknowledged after the last listener returned");
        assertTrue(ack.getEventTimeNanos() >= applied.getReceiveTimeNanos() + 2 * APPLYING_MILLIS * 1_000_000,
                "the apply time is when the listeners were done, not the receive time");
        assertTrue(ack.getEventTimeNanos() <= ack.getPublishTimeNanos());
        assertNull(acks.poll(300), "one acknowledgement per member and message");
        assertEquals(0, tester.getStats().getRejectedTotal(), tester.getStats().toString());

        // an adapter's own messages and those of other members than the tester are no inputs to acknowledge
        Inbox dones = new Inbox(DONE);
        adapter.addDtronListener(dones);
        adapter.send(DONE.constructValued(Map.of("amount", 3)));
        dones.take();
        try (Dtron other = Dtron.connect(TestClusters.inJvm(cluster).memberName("other").build())) {
            other.send(MOVE.constructValued(Map.of("amount", 4)));
            assertEquals(4, first.received.poll(10, TimeUnit.SECONDS).getVariables().get("amount"));
        }
        assertNull(acks.poll(300), "only the tester's inputs are acknowledged");

        tester.send(Dtron.RUN_STOP.constructValued(Map.of()));
        testerStops.take();
        tester.send(MOVE.constructValued(Map.of("amount", 5)));
        assertEquals(5, first.received.poll(10, TimeUnit.SECONDS).getVariables().get("amount"));
        assertNull(acks.poll(300), "after the run, no acknowledgement");
    }

    @Test
    void aListenerThatOptsOutAcknowledgesItselfOnce() throws Exception {
        Applier manual = new Applier(false);
        Applier automatic = new Applier(true);
        adapter.addDtronListener(manual);
        adapter.addDtronListener(automatic);
        startRun();
        tester.send(MOVE.constructValued(Map.of("amount", 1)));
        IDtronChannelValued input = manual.received.poll(10, TimeUnit.SECONDS);
        assertNull(acks.poll(2 * APPLYING_MILLIS + 300), "one listener opted out: no automatic acknowledgement");

        long appliedAt = input.getReceiveTimeNanos() + 1_234_567;
        ClockOffsetTest.awaitOffset(adapter);
        assertTrue(adapter.acknowledge(input, appliedAt));
        IDtronChannelValued ack = acks.take();
        assertEquals(appliedAt, ack.getEventTimeNanos());
        assertEquals("tester", ack.getAckedSender());
        assertEquals(input.getSequence(), ack.getAckedSequence());
        assertTrue(ack.getClockErrorNanos() > 0, "the adapter's offset estimate travels with its acknowledgement");
        assertTrue(Math.abs(ack.getClockOffsetNanos() + 20_000_000) <= ack.getClockErrorNanos(),
                ack.getClockOffsetNanos() + " +/- " + ack.getClockErrorNanos());
        assertFalse(adapter.acknowledge(input), "a message is acknowledged once");
        assertNull(acks.poll(300));
    }

    @Test
    void aListenerMayAcknowledgeEarlierThanItReturns() throws Exception {
        BlockingQueue<Long> acknowledgedAt = new LinkedBlockingQueue<>();
        adapter.addDtronListener(new DtronListener(MOVE) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                long at = getDtron().currentTimeNanos();
                assertTrue(getDtron().acknowledge(message, at));
                acknowledgedAt.add(at);
                try {
                    Thread.sleep(APPLYING_MILLIS);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            }
        });
        startRun();
        tester.send(MOVE.constructValued(Map.of("amount", 1)));
        IDtronChannelValued ack = acks.take();
        assertEquals(acknowledgedAt.poll(10, TimeUnit.SECONDS), ack.getEventTimeNanos());
        assertNull(acks.poll(APPLYING_MILLIS + 300), "not acknowledged again when the listener returned");
    }

    @Test
    void aProbeAsAnInputIsAnsweredOnTheListenersThreadInOrderWithoutReachingAListener() throws Exception {
        Applier applier = new Applier(true);
        adapter.addDtronListener(applier);
        List<BusRecord> records = new CopyOnWriteArrayList<>();
        tester.addRecordListener(records::add);
        ClockOffsetTest.awaitOffset(adapter);
        startRun();
        tester.send(MOVE.constructValued(Map.of("amount", 1)));
        // the probe comes while the listener applies the move: its answer waits for it, as an input would
        assertEquals(Set.of("adapter"), TesterSide.of(tester).probeAsInput(List.of("adapter"), Duration.ofSeconds(10)));
        long moveApplied = applier.returnedAt.poll(10, TimeUnit.SECONDS);

        BusRecord ping = records.stream().filter(r -> r.channel().equals("dtron_ping") && r.sender().equals("tester"))
                .reduce((first, last) -> last).orElseThrow();
        List<BusRecord> answers = records.stream().filter(r -> r.ackedSender().equals("tester")
                && r.ackedSequence() == ping.sequence()).toList();
        assertEquals(1, answers.size(), answers.toString());
        BusRecord answer = answers.get(0);
        assertEquals(Dtron.ACK.getChannelName(), answer.channel(), "answered as an input is: acknowledged, no pong");
        assertEquals("adapter", answer.sender());
        assertTrue(answer.eventTimeNanos() >= moveApplied, "answered on the listeners' thread, after the move");
        assertTrue(answer.clockErrorNanos() > 0, "the answer carries the adapter's clock offset, as an input's does");

        assertEquals(1, applier.received.size(), "no listener heard the probe");
        IDtronChannelValued moveAck = acks.take();
        assertEquals("tester", moveAck.getAckedSender());
        assertTrue(moveAck.getAckedSequence() != ping.sequence());
        assertNull(acks.poll(300), "the probe's answer is no input's acknowledgement: the tester's listeners miss it");
        assertEquals(0, tester.getStats().getRejectedTotal(), tester.getStats().toString());
        assertEquals(0, adapter.getStats().getRejectedTotal(), adapter.getStats().toString());
    }

    @Test
    void aMemberThatAnswersPingsWithPongsAnswersAProbeAsAnInput() throws Exception {
        // a tester answers every ping with a pong, as an adapter built against an older API does
        try (Dtron other = Dtron.connect(TestClusters.inJvm(cluster).memberName("other").tester(true).build())) {
            assertTrue(tester.awaitMembers(3, Duration.ofSeconds(10)));
            assertEquals(Set.of("other"), TesterSide.of(tester).probeAsInput(List.of("other"), Duration.ofSeconds(10)));
        }
    }

    @Test
    void onlyMessagesFromTheBusOnModelChannelsCanBeAcknowledged() throws Exception {
        assertThrows(IllegalArgumentException.class,
                () -> adapter.acknowledge(MOVE.constructValued(Map.of("amount", 1))));
        Inbox starts = new Inbox(Dtron.RUN_START);
        adapter.addDtronListener(starts);
        tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 1_000)));
        IDtronChannelValued start = starts.take();
        assertThrows(IllegalArgumentException.class, () -> adapter.acknowledge(start));
        assertThrows(IllegalArgumentException.class, () -> adapter.send(Dtron.ACK.constructValued(Map.of())));
    }
}
