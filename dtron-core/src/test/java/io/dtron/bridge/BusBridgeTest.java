package io.dtron.bridge;

import io.dtron.api.internal.TesterSide;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import ch.qos.logback.classic.Level;
import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.DtronStats;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.api.internal.BusConnector;
import io.dtron.api.internal.proto.Sync;
import io.dtron.api.internal.proto.Variable;
import io.dtron.bus.internal.Transport;
import io.dtron.bus.internal.JGroupsTransport;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.TestInterface;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.LogCapture;
import io.dtron.testsupport.Waits;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.EnumSource;

/** The bridge on the in-JVM bus, with a stand-in for the engine's side. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class BusBridgeTest {
    private static final Duration WAIT = Duration.ofSeconds(10);
    private static final String MODEL = """
            chan i_move, o_done, i_x, o_x;
            int i_move_amount; int o_done_amount;
            process P() { state A; init A;
                trans A -> A { sync i_move?; }, A -> A { sync o_done!; }, A -> A { sync i_x?; }, A -> A { sync o_x!; };
            }
            system P;
            """;
    private static final String EMPTY = " process P() { state A; init A; } system P;";
    private static final IDtronChannel MOVE = IDtronChannel.of("move", "amount");
    private static final IDtronChannel DONE = IDtronChannel.of("done", "amount");
    private static final IDtronChannel X = IDtronChannel.of("x");

    private final String cluster = "bridge-" + UUID.randomUUID().toString().substring(0, 8);
    private final Context context = new Context();
    private BusBridge bridge;
    private Dtron adapter;

    /** The engine's side: keeps what the bridge reports, with a real clock from its creation. */
    private static final class Context implements AdapterContext {
        final BlockingQueue<Event> outputs = new LinkedBlockingQueue<>();
        final BlockingQueue<Long> outputTimes = new LinkedBlockingQueue<>();
        final BlockingQueue<long[]> applied = new LinkedBlockingQueue<>();
        final BlockingQueue<String> inconclusive = new LinkedBlockingQueue<>();
        final BlockingQueue<Long> uncertainties = new LinkedBlockingQueue<>();
        final BlockingQueue<Long> widened = new LinkedBlockingQueue<>();
        final long zero = System.nanoTime();

        @Override
        public void report(Event output) {
            throw new AssertionError("the bridge reports outputs with their event times");
        }

        @Override
        public void report(Event output, long eventMicros) {
            outputTimes.add(eventMicros);
            outputs.add(output);
        }

        @Override
        public void report(Event output, long eventMicros, long uncertaintyMicros) {
            uncertainties.add(uncertaintyMicros);
            report(output, eventMicros);
        }

        @Override
        public void inputApplied(long ordinal, long eventMicros) {
            applied.add(new long[] {ordinal, eventMicros});
        }

        @Override
        public void inputApplied(long ordinal, long eventMicros, long uncertaintyMicros) {
            uncertainties.add(uncertaintyMicros);
            inputApplied(ordinal, eventMicros);
        }

        @Override
        public void widenReorderWindow(long micros) {
            widened.add(micros);
        }

        @Override
        public void inconclusive(String reason) {
            inconclusive.add(reason);
        }

        @Override
        public TestClock clock() {
            return new TestClock() {
                @Override
                public long nowMicros() {
                    return (System.nanoTime() - zero) / 1000;
                }

                @Override
                public Scheduled schedule(long delayMicros, Runnable task) {
                    throw new UnsupportedOperationException("the bridge schedules nothing");
                }
            };
        }

        @Override
        public TestInterface testInterface() {
            throw new UnsupportedOperationException("the bridge gets the interface when it connects");
        }

        @Override
        public long timeUnitMicros() {
            return 250;
        }
    }

    @BeforeEach
    void connect() throws Exception {
        bridge = BusBridge.connect(testInterface(MODEL), DtronOptions.builder().clusterName(cluster).inJvm(true));
        adapter = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("adapter").inJvm(true).build());
        assertTrue(bridge.run().awaitAdapters(1, WAIT));
    }

    @AfterEach
    void close() {
        adapter.close();
        bridge.close();
    }

    private static TestInterface testInterface(String model) throws ModelException {
        return TestInterface.fromNames(ModelLoader.load("bridge.xta", model));
    }

    @Test
    void announcesTheStartPublishesInputsAndReportsOutputs() throws Exception {
        Inbox start = new Inbox(Dtron.RUN_START);
        Inbox stop = new Inbox(Dtron.RUN_STOP);
        Inbox moves = new Inbox(MOVE);
        adapter.addDtronListener(start);
        adapter.addDtronListener(stop);
        adapter.addDtronListener(moves);
        bridge.start(context);
        IDtronChannelValued announced = start.take();
        assertEquals(Map.of("timeunit", 250), announced.getVariables());
        assertEquals(bridge.run().memberId(), announced.getSender());

        bridge.perform(Event.of("move", "amount", 7));
        IDtronChannelValued move = moves.take();
        assertEquals(7, move.getVariables().get("amount"));
        adapter.send(DONE.constructValued(Map.of("amount", 14)));
        assertEquals(Event.of("done", "amount", 14), context.outputs.poll(10, TimeUnit.SECONDS));
        assertNull(context.outputs.poll(200, TimeUnit.MILLISECONDS), "the bridge's own input is no output");

        assertEquals(1, bridge.run().outputLatency().count());
        assertTrue(bridge.run().outputLatency().minMicros() >= 0, bridge.run().outputLatency().toString());
        assertEquals(1, bridge.run().inputLatency().count(), "the input came back through the bus");
        bridge.stop();
        assertEquals(bridge.run().memberId(), stop.take().getSender(), "the end of the run is announced");
        DtronStats stats = bridge.run().stats();
        assertEquals(3, stats.getPublished(), stats.toString());
        assertEquals(0, stats.getRejectedTotal(), stats.toString());
        assertTrue(context.inconclusive.isEmpty(), context.inconclusive.toString());
    }

    @Test
    void outputsAreReportedAtTheTimeTheirSenderStampedOnTheRunsClock() throws Exception {
        Inbox start = new Inbox(Dtron.RUN_START);
        adapter.addDtronListener(start);
        bridge.start(context);
        long zero = start.take().getEventTimeNanos();
        long before = context.clock().nowMicros();
        // an output the system produced 7 ms after time 0, published later
        adapter.send(DONE.constructValued(Map.of("amount", 1)), zero + 7_000_000);
        assertEquals(Event.of("done", "amount", 1), context.outputs.poll(10, TimeUnit.SECONDS));
        long at = context.outputTimes.take();
        // on one host only the adapter's estimate of its offset to the tester's clock (within its error) differs
        long error = adapter.getClockOffset().map(o -> o.errorNanos() / 1000).orElse(0L) + 1000;
        assertTrue(Math.abs(at - 7000) <= error, "reported at " + at + " us, stamped at 7000 us (error " + error
                + " us); time 0 was " + before + " us before the send on the run's clock");
    }

    /** Waits until the adapter has an estimate of its clock offset to the tester. */
    private void awaitOffset() {
        Waits.await("the adapter's clock offset estimate").until(adapter::hasClockOffset);
    }

    @Test
    void anEventsTimeIsUncertainByItsSendersClockError() throws Exception {
        awaitOffset();
        bridge.start(context);
        IDtronChannelValued sent = adapter.send(DONE.constructValued(Map.of("amount", 1)));
        assertNotNull(context.outputs.poll(10, TimeUnit.SECONDS));
        long uncertainty = context.uncertainties.take();
        assertTrue(sent.getClockErrorNanos() > 0, "an estimate has an error bound");
        assertEquals((sent.getClockErrorNanos() + 999) / 1000, uncertainty, "the error bound in whole us, rounded up");
    }

    @Test
    void anAutomaticWindowIsWidenedByAMessageThatTookMoreThanHalfOfIt() throws Exception {
        awaitOffset();
        bridge.run().reorderWindow(40_000, true);
        Inbox start = new Inbox(Dtron.RUN_START);
        adapter.addDtronListener(start);
        bridge.start(context);
        start.take();
        // produced 30 ms before it is sent: more than half of 40 ms
        adapter.send(X.constructValued(Map.of()), adapter.currentTimeNanos() - 30_000_000);
        long widened = context.widened.poll(10, TimeUnit.SECONDS);
        assertTrue(widened >= 50_000 && widened % 1000 == 0, "twice the delay, in whole ms: " + widened);
        assertEquals(widened, bridge.run().reorderWindowMicros());
        assertEquals(1, bridge.run().widenings().size(), bridge.run().widenings().toString());
        assertTrue(bridge.run().widenings().get(0).contains("output x from adapter took "),
                bridge.run().widenings().toString());
        assertTrue(bridge.run().runDelays().get(0).highMicros() >= 25_000, "30 ms, give or take the clocks' error: "
                + bridge.run().runDelays());
        assertEquals("output", bridge.run().runDelays().get(0).direction());
        // a delay within half of the wider window changes nothing; a loaded machine may hold the message up for
        // longer than that (its delay is produced-to-received), and then it widens the window by its real delay
        long wider = bridge.run().reorderWindowMicros();
        adapter.send(X.constructValued(Map.of()), adapter.currentTimeNanos() - 5_000_000);
        assertNotNull(context.outputs.poll(10, TimeUnit.SECONDS));
        assertNotNull(context.outputs.poll(10, TimeUnit.SECONDS));
        List<String> widenings = bridge.run().widenings();
        long longest = bridge.run().runDelays().get(0).highMicros();
        if (widenings.size() > 1) {
            assertEquals(2, widenings.size(), widenings.toString());
            assertTrue(longest > wider / 2 - 1000, "widened again although the second output took " + longest
                    + " us, within half of " + wider + " us (give or take the clocks' error): " + widenings);
            assertTrue(bridge.run().reorderWindowMicros() > wider, widenings.toString());
        }
    }

    @Test
    void aFixedWindowIsNotWidened() throws Exception {
        awaitOffset();
        bridge.run().reorderWindow(40_000, false);
        bridge.start(context);
        adapter.send(X.constructValued(Map.of()), adapter.currentTimeNanos() - 30_000_000);
        assertNotNull(context.outputs.poll(10, TimeUnit.SECONDS));
        assertTrue(context.widened.isEmpty(), context.widened.toString());
        assertEquals(40_000, bridge.run().reorderWindowMicros());
        assertTrue(bridge.run().runDelays().get(0).highMicros() >= 25_000, "30 ms, give or take the clocks' error: "
                + bridge.run().runDelays());
        assertEquals("output", bridge.run().runDelays().get(0).direction());
    }

    @Test
    void delaysAreMeasuredBeforeARun() throws Exception {
        awaitOffset();
        BusRun.Delays delays = bridge.run().measureDelays(3, Duration.ofMillis(10));
        assertEquals(1, delays.members(), delays.toString());
        assertTrue(delays.messages() >= 3, "at least the answers to the probes: " + delays);
        assertTrue(delays.maxDelayNanos() < TimeUnit.SECONDS.toNanos(1), delays.toString());
        assertTrue(delays.maxErrorNanos() > 0, delays.toString());
    }

    @Test
    void probesGoOnUntilSteadyWithinTheirLimitAndGiveTheRoomOfTheInputs() throws Exception {
        awaitOffset();
        BusRun.Probing probing = bridge.run().probeUntilSteady(Duration.ofMillis(5), Duration.ofMillis(50),
                Duration.ofSeconds(2));
        assertTrue(probing.rounds() >= 1, probing.toString());
        // steady takes twice five rounds at least; else the limit ended them (plus a round of at most a second)
        assertTrue(probing.steady() ? probing.rounds() >= 10 : probing.millis() >= 2_000, probing.toString());
        assertTrue(probing.millis() >= 50, probing.toString());
        assertTrue(probing.lastMicros() > 0, probing.toString());
        // the adapter receives move: its longest round trip of the last rounds is the room of move
        long room = bridge.inputDelayMicros("move");
        assertTrue(room > 0 && room <= probing.lastMicros(), room + " us, " + probing);
    }

    @Test
    void inputsAreAcknowledgedWhereTheAdapterAppliedThem() throws Exception {
        Inbox moves = new Inbox(MOVE);
        adapter.addDtronListener(moves);
        bridge.start(context);
        bridge.perform(Event.of("move", "amount", 1));
        bridge.perform(Event.of("move", "amount", 2));
        long[] first = context.applied.poll(10, TimeUnit.SECONDS);
        long[] second = context.applied.poll(10, TimeUnit.SECONDS);
        assertNotNull(second, "both inputs acknowledged");
        assertEquals(1, first[0], "inputs are numbered from 1, in the order performed");
        assertEquals(2, second[0]);
        assertTrue(first[1] >= 0 && first[1] <= second[1] + 1000, first[1] + " " + second[1]);
        assertTrue(second[1] <= context.clock().nowMicros() + 1000, "applied before now: " + second[1]);
        // the inputs' delays, published to applied, make the channel's interval
        ChannelDelay delay = bridge.run().runDelays().get(0);
        assertEquals("move", delay.channel());
        assertEquals("input", delay.direction());
        assertEquals(2, delay.count());
        assertTrue(delay.lowMicros() <= delay.highMicros() && delay.highMicros() < 10_000_000, delay.toString());
    }

    @Test
    void messagesOfAnotherRunAreIgnoredAndCounted() throws Exception {
        bridge.start(context);
        try (Dtron other = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("other-run")
                .inJvm(true).build())) {
            TesterSide.of(other).setRunId("another-run");
            other.send(DONE.constructValued(Map.of("amount", 5)));
            adapter.send(DONE.constructValued(Map.of("amount", 6)));
            assertEquals(Event.of("done", "amount", 6), context.outputs.poll(10, TimeUnit.SECONDS),
                    "the other run's output is not this run's");
            Waits.await("the other run's message counted").until(() -> bridge.run().messagesOfOtherRuns() >= 1);
            assertEquals(1, bridge.run().messagesOfOtherRuns());
            assertTrue(context.outputs.isEmpty(), context.outputs.toString());
        }
    }

    @Test
    void onAChannelThatIsInputAndOutputOnlyOtherMembersMessagesAreOutputs() throws Exception {
        Inbox xs = new Inbox(X);
        adapter.addDtronListener(xs);
        bridge.start(context);
        bridge.perform(Event.of("x"));
        assertEquals(bridge.run().memberId(), xs.take().getSender());
        adapter.send(X.constructValued(Map.of()));
        assertEquals(Event.of("x"), context.outputs.poll(10, TimeUnit.SECONDS));
        assertNull(context.outputs.poll(200, TimeUnit.MILLISECONDS), "one output only: " + context.outputs);
    }

    @Test
    void outputsBeforeTheStartAndAfterTheStopAreNotReported() throws Exception {
        adapter.send(DONE.constructValued(Map.of("amount", 1)));
        awaitOutputsSeen(1);
        bridge.start(context);
        bridge.stop();
        assertEquals(0, bridge.run().outputsAfterEnd());
        try (LogCapture log = new LogCapture(BusRun.class)) {
            adapter.send(DONE.constructValued(Map.of("amount", 2)));
            adapter.send(DONE.constructValued(Map.of("amount", 3)));
            awaitOutputsSeen(3);
            assertEquals(2, bridge.run().outputsAfterEnd(), "outputs after the end are counted");
            assertTrue(log.events(Level.WARN).isEmpty(), "and not logged as warnings after the verdict: "
                    + log.messages());
        }
        assertTrue(context.outputs.isEmpty(), context.outputs.toString());
    }

    /**
     * The four kinds of bad input of a member of the bus: each is rejected and counted, and the next output is still
     * reported. (What has no valid code of the bus's secret the transport drops before: NatsSecurityTest.)
     */
    @ParameterizedTest
    @EnumSource(value = Reason.class, names = {"MALFORMED", "UNKNOWN_CHANNEL", "UNKNOWN_VARIABLES",
            "MISSING_VARIABLES"})
    void badMessagesAreRejectedCountedAndTheRunGoesOn(Reason reason) throws Exception {
        bridge.start(context);
        try (Transport rogue = JGroupsTransport.connect(BusConnector.settings(
                DtronOptions.builder().clusterName(cluster).inJvm(true).build(), "rogue"))) {
            switch (reason) {
                case MALFORMED -> rogue.publish("done", new byte[] {(byte) 0xFF, (byte) 0xFF, 0x07});
                case UNKNOWN_CHANNEL -> rogue.publish("bogus", sync("bogus"));
                case UNKNOWN_VARIABLES -> rogue.publish("done", sync("done", variable("amount", 1),
                        variable("colour", 2)));
                case MISSING_VARIABLES -> rogue.publish("done", sync("done"));
                default -> throw new AssertionError(reason);
            }
            adapter.send(DONE.constructValued(Map.of("amount", 3)));
            assertEquals(Event.of("done", "amount", 3), context.outputs.poll(10, TimeUnit.SECONDS));
            assertNull(context.outputs.poll(100, TimeUnit.MILLISECONDS), "the bad message is no output");
            DtronStats stats = bridge.run().stats();
            assertEquals(1, stats.getRejected(reason), stats.toString());
            assertEquals(1, stats.getRejectedTotal(), stats.toString());
            assertEquals(1, bridge.run().outputLatency().count());
        }
    }

    /** The adapter says it sends {@code done}, and the bridge has heard it: it serves the run. */
    private void adapterServesDone() {
        adapter.declareOutputs(DONE);
        Waits.await("the adapter's channels").until(() -> bridge.run().servedChannels().containsKey("adapter")
                && bridge.run().servedChannels().get("adapter").sends().contains("done"));
    }

    @Test
    void aMemberLeavingDuringTheRunEndsItInconclusive() throws Exception {
        adapterServesDone();
        bridge.start(context);
        adapter.close();
        String reason = context.inconclusive.poll(10, TimeUnit.SECONDS);
        assertNotNull(reason, "no inconclusive verdict");
        assertTrue(reason.startsWith("adapter member adapter left the bus (members now [" + bridge.run().memberId()
                + "])"),
                reason);
    }

    @Test
    void aMemberThatJoinedDuringTheRunAndLeftIsNoReason() throws Exception {
        adapterServesDone();
        bridge.start(context);
        // a member that never served the run: a tester refused because this run is going on, or its adapter
        try (Dtron newcomer = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("newcomer")
                .inJvm(true).build())) {
            awaitMembers(3);
        }
        awaitMembers(2);
        // membership news comes in the bus's order: the first reason must be the served adapter's leaving
        adapter.close();
        String reason = context.inconclusive.poll(10, TimeUnit.SECONDS);
        assertNotNull(reason, "no inconclusive verdict");
        assertTrue(reason.startsWith("adapter member adapter left the bus"), reason);
    }

    @Test
    void aMemberThatServesNoChannelOfTheModelMayLeaveDuringTheRun() throws Exception {
        adapterServesDone();
        try (Dtron observer = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("observer")
                .inJvm(true).build())) {
            // it watches an output and listens to a channel of no model: it applies no input, sends no output
            observer.addDtronListener(new Inbox(DONE));
            observer.addDtronListener(new Inbox(IDtronChannel.of("weather")));
            // what the bus told the tester's member; the start catches its listeners' thread up with it, so the run
            // decides on the same view that the observer serves no channel of the model
            Waits.await("the observer's channels").until(() -> bridge.run().servedChannels().containsKey("observer")
                    && bridge.run().servedChannels().get("observer").receives().contains("weather"));
            bridge.start(context);
        }
        awaitMembers(2);
        adapter.close();
        String reason = context.inconclusive.poll(10, TimeUnit.SECONDS);
        assertNotNull(reason, "no inconclusive verdict");
        assertTrue(reason.startsWith("adapter member adapter left the bus"), "the observer is no reason: " + reason);
    }

    @Test
    void aSecondMemberSendingAnOutputDuringTheRunEndsItInconclusiveNamingBoth() throws Exception {
        adapterServesDone();
        assertEquals(java.util.Optional.empty(), bridge.run().ownersConflict());
        bridge.start(context);
        try (Dtron second = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("second")
                .inJvm(true).build())) {
            second.send(DONE.constructValued(Map.of("amount", 1)));
            String reason = context.inconclusive.poll(10, TimeUnit.SECONDS);
            assertEquals("output done is sent by 2 members, adapter (receives [], sends [done]) and second (receives"
                    + " [], sends [done]), and the tester would judge their messages as one system's", reason);
            assertTrue(bridge.run().ownersConflict().isPresent(), "and a run would be refused now");
            // its message came after it said it sends done: named, and no output
            assertNull(context.outputs.poll(200, TimeUnit.MILLISECONDS), context.outputs.toString());
        }
        Waits.await("the second member gone").until(() -> bridge.run().ownersConflict().isEmpty());
    }

    @Test
    void anOutputFromAMemberThatDidNotSayItSendsItIsNotJudged() throws Exception {
        adapterServesDone();
        bridge.start(context);
        try (Transport old = JGroupsTransport.connect(BusConnector.settings(
                DtronOptions.builder().clusterName(cluster).inJvm(true).build(), "old"))) {
            old.publish("done", sync("done", variable("amount", 2)));
            String reason = context.inconclusive.poll(10, TimeUnit.SECONDS);
            assertEquals("member old, which did not say what it serves, sent output done, which adapter (receives [],"
                    + " sends [done]) sends: the tester cannot judge their messages as one system's", reason);
            assertTrue(context.outputs.isEmpty(), context.outputs.toString());
        }
    }

    @Test
    void anInputFromAnotherMemberDuringTheRunEndsItInconclusiveNamingIt() throws Exception {
        bridge.start(context);
        adapter.send(MOVE.constructValued(Map.of("amount", 2)));
        String reason = context.inconclusive.poll(10, TimeUnit.SECONDS);
        assertEquals("adapter (receives [], sends [move]) sent input move, which only the tester sends: the system"
                + " under test may have applied an input the model did not choose", reason);
        assertTrue(context.outputs.isEmpty(), context.outputs.toString());
    }

    @Test
    void membersLeavingBeforeTheStartOrAfterTheStopAreNoReason() throws Exception {
        try (Dtron early = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build())) {
            assertTrue(bridge.run().awaitAdapters(2, WAIT));
        }
        awaitMembers(2);
        bridge.start(context);
        bridge.stop();
        adapter.close();
        awaitMembers(1);
        assertNull(context.inconclusive.poll(200, TimeUnit.MILLISECONDS));
    }

    @Test
    void anAwaitedAdapterThatLeftBeforeTheStartEndsTheRunInconclusiveAtOnce() throws Exception {
        try (Dtron early = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build())) {
            assertTrue(bridge.run().awaitAdapters(2, WAIT));
            bridge.run().expectAdapters();
        }
        awaitMembers(2);
        bridge.start(context);
        String reason = context.inconclusive.poll(10, TimeUnit.SECONDS);
        assertNotNull(reason, "no inconclusive verdict");
        assertTrue(reason.matches("adapter member \\S+ left the bus before the run started \\(members now \\[.*]\\);"
                + " the system under test may be gone"), reason);
        assertFalse(reason.contains("member adapter "), "the adapter still on the bus is not named: " + reason);
    }

    private void awaitMembers(int count) {
        Waits.await(count + " members").until(() -> bridge.run().members().size() == count);
    }

    @Test
    void interfaceChannelsThatCannotTravelOnTheBusAreRefused() {
        IllegalArgumentException reserved = assertThrows(IllegalArgumentException.class, () -> BusBridge.connect(
                testInterface("chan i_dtron_start;" + EMPTY), DtronOptions.builder().inJvm(true)));
        assertTrue(reserved.getMessage().contains("reserves for announcing the start and end of a run"),
                reserved.getMessage());
        IllegalArgumentException reservedStop = assertThrows(IllegalArgumentException.class, () -> BusBridge
                .connect(testInterface("chan o_dtron_stop;" + EMPTY), DtronOptions.builder().inJvm(true)));
        assertTrue(reservedStop.getMessage().contains("channel 'dtron_stop' of the model's interface has a name DTRON"
                + " reserves"), reservedStop.getMessage());
        IllegalArgumentException array = assertThrows(IllegalArgumentException.class, () -> BusBridge.connect(
                testInterface("chan i_req[2];" + EMPTY), DtronOptions.builder().inJvm(true)));
        assertTrue(array.getMessage().contains("channel 'req[0]' of the model's interface cannot travel on the bus"),
                array.getMessage());
        IllegalArgumentException clash = assertThrows(IllegalArgumentException.class, () -> BusBridge.connect(
                testInterface("chan i_y, o_y; int i_y_a;" + EMPTY), DtronOptions.builder().inJvm(true)));
        assertTrue(clash.getMessage().contains("input and output 'y' carry different variables ([a], [])"),
                clash.getMessage());
    }

    /** Waits until the bridge has handled {@code count} outputs (it records the latency of each). */
    private void awaitOutputsSeen(long count) {
        Waits.await(count + " outputs handled").until(() -> bridge.run().outputLatency().count() >= count);
        assertEquals(count, bridge.run().outputLatency().count());
    }

    private static Variable variable(String name, int value) {
        return Variable.newBuilder().setName(name).setValue(value).build();
    }

    private static byte[] sync(String name, Variable... variables) {
        return Sync.newBuilder().setName(name).addAllVariables(List.of(variables)).build().toByteArray();
    }
}
