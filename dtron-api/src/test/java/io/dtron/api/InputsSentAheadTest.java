package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.internal.TesterSide;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.Waits;
import java.util.List;
import java.util.Map;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * A tester's inputs sent ahead of their time ({@link TesterSide#sendAhead}): a member holds each until it is due on
 * its run clock, then hands it to its listeners and acknowledges it, and what the bus ordered after it waits behind
 * it. Both members read the same wall clock, so that their run clocks agree exactly.
 */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class InputsSentAheadTest {
    private static final IDtronChannel MOVE = IDtronChannel.of("move", "amount");
    private static final long AHEAD_NANOS = 300_000_000;
    private final String cluster = TestClusters.uniqueName("ahead");
    private Dtron tester;
    private Dtron adapter;
    private Inbox acks;
    /** What the adapter's listener was handed: the amount, and the run time then. */
    private final BlockingQueue<long[]> heard = new LinkedBlockingQueue<>();
    /** The threads the adapter's listener was called on, in order. */
    private final BlockingQueue<String> threads = new LinkedBlockingQueue<>();
    /** Time 0 of the run, on the tester's wall clock. */
    private long zeroEpoch;

    @BeforeEach
    void connect() throws InterruptedException {
        tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true)
                .channels(List.of(MOVE, Dtron.RUN_START, Dtron.RUN_STOP)).build());
        adapter = Dtron.connect(TestClusters.inJvm(cluster).memberName("adapter").build());
        acks = new Inbox(Dtron.ACK);
        tester.addDtronListener(acks);
        adapter.addDtronListener(new DtronListener(MOVE) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                heard.add(new long[] {message.getVariables().get("amount"), getDtron().runClock().nowNanos()});
                threads.add(Thread.currentThread().getName());
            }
        });
        Inbox starts = new Inbox(Dtron.RUN_START);
        adapter.addDtronListener(starts);
        tester.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 1_000)));
        zeroEpoch = starts.take().getEventTimeNanos();
        adapter.removeDtronListener(starts);
    }

    @AfterEach
    void close() {
        adapter.close();
        tester.close();
    }

    @Test
    void aMemberSaysInTheHandshakeThatItHoldsInputs() {
        Waits.await("the adapter's part of the handshake").until(() -> TesterSide.of(tester).holdsInputs("adapter"));
        assertFalse(TesterSide.of(tester).holdsInputs("nobody"));
    }

    @Test
    void anInputSentAheadIsHeardAtItsDueTimeAndWhatFollowsItWaitsBehindIt() throws Exception {
        long dueEpoch = tester.currentTimeNanos() + AHEAD_NANOS;
        IDtronChannelValued ahead = TesterSide.of(tester).sendAhead(MOVE.constructValued(Map.of("amount", 1)),
                dueEpoch);
        assertEquals(dueEpoch, ahead.getDueTimeNanos());
        tester.send(MOVE.constructValued(Map.of("amount", 2)));
        long dueRun = dueEpoch - zeroEpoch;
        long[] first = heard.poll(30, TimeUnit.SECONDS);
        long[] second = heard.poll(30, TimeUnit.SECONDS);
        assertEquals(1, first[0], "the input sent ahead comes first, as the bus ordered it");
        assertTrue(first[1] >= dueRun, "heard at " + first[1] + " ns of the run, due at " + dueRun);
        assertEquals(2, second[0]);
        // the input sent ahead is handed over by the run clock's thread, which spins the last stretch before it
        assertTrue(threads.take().startsWith("dtron-run-clock-"), "called on the run clock's thread");
        assertTrue(threads.take().startsWith("dtron-listeners-"), "the next on the listeners' thread");
        assertTrue(second[1] >= first[1], "the next input waited behind it");
        IDtronChannelValued ack = acks.take();
        assertEquals(ahead.getSequence(), ack.getAckedSequence());
        assertTrue(ack.getEventTimeNanos() >= dueEpoch, "applied at " + ack.getEventTimeNanos() + ", due at "
                + dueEpoch);
    }

    @Test
    void onlyAModelInputWithAPositiveDueTimeIsSentAhead() {
        TesterSide side = TesterSide.of(tester);
        assertThrows(IllegalArgumentException.class, () -> side.sendAhead(MOVE.constructValued(Map.of("amount", 1)),
                0));
        assertThrows(IllegalArgumentException.class, () -> side.sendAhead(Dtron.RUN_STOP.constructValued(Map.of()),
                tester.currentTimeNanos()));
    }
}
