package io.dtron.api;

import io.dtron.api.internal.TesterSide;
import static org.awaitility.Awaitility.await;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import ch.qos.logback.classic.Level;
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
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * Two testers on one bus, each with its own model's channels, as in a distributed run: a message on the other
 * tester's channel is neither rejected, logged nor counted, and is handed to the record listeners (the trace) in
 * the bus's order; a message on a channel no tester serves is still rejected.
 */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class OtherTestersChannelsTest {
    private final IDtronChannel move = IDtronChannel.of("move", "amount");
    private final IDtronChannel done = IDtronChannel.of("done", "amount");
    private final String cluster = TestClusters.uniqueName("otherTesters");

    @Test
    void anotherTestersChannelIsTracedNotRejectedAndAnUndeclaredOneStillIs() throws Exception {
        DtronOptions injectorOptions = TestClusters.inJvm(cluster).build();
        LinkedBlockingQueue<BusRecord> records = new LinkedBlockingQueue<>();
        try (LogCapture log = new LogCapture(Dtron.class);
                Transport injector = JGroupsTransport.connect(BusConnector.settings(injectorOptions, "injector"));
                Dtron first = Dtron.connect(TestClusters.inJvm(cluster).tester(true).channels(List.of(move))
                        .build());
                Dtron second = Dtron.connect(TestClusters.inJvm(cluster).tester(true).channels(List.of(done))
                        .build())) {
            Inbox moves = new Inbox(move);
            first.addDtronListener(moves);
            second.addDtronListener(new Inbox(done));   // the second tester receives done: its model's output
            TesterSide firstTester = TesterSide.of(first);
            TesterSide secondTester = TesterSide.of(second);
            await().atMost(Duration.ofSeconds(20)).until(() -> firstTester.getOtherTesters()
                    .contains(second.getMemberId())
                    && firstTester.getMembersServedChannels().containsKey(second.getMemberId())
                    && firstTester.getMembersServedChannels().get(second.getMemberId()).receives().contains("done")
                    && secondTester.getOtherTesters().contains(first.getMemberId())
                    && secondTester.getMembersServedChannels().containsKey(first.getMemberId())
                    && secondTester.getMembersServedChannels().get(first.getMemberId()).receives().contains("move"));
            first.addRecordListener(r -> {
                if (!Dtron.isReservedChannel(r.channel())) {
                    records.add(r);
                }
            });

            injector.publish("done", sync("done", 7));
            injector.publish("bogus", sync("bogus", 1));
            injector.publish("move", sync("move", 3));
            assertEquals(3, moves.take().getVariables().get("amount"));

            BusRecord traced = records.take();
            assertEquals("done", traced.channel(), "the other tester's message comes first, in the bus's order");
            assertEquals(Map.of("amount", 7), traced.variables());
            assertEquals("injector", traced.sender());
            assertEquals("move", records.take().channel(), "the rejected message is not traced");
            DtronStats stats = first.getStats();
            assertEquals(1, stats.getRejectedTotal(), "only bogus is rejected: " + stats);
            assertEquals(1, stats.getRejected(Reason.UNKNOWN_CHANNEL), stats.toString());
            assertEquals(1, stats.getAccepted(), "the other tester's message is not counted: " + stats);
            assertEquals(1, second.getStats().getRejectedTotal(), "the second rejects bogus, not move: "
                    + second.getStats());
            List<String> rejections = log.events(Level.WARN).stream().map(e -> e.getFormattedMessage())
                    .filter(m -> m.startsWith("Rejected")).toList();
            assertEquals(2, rejections.size(), "bogus, once by each tester: " + rejections);
            assertTrue(rejections.stream().allMatch(m -> m.contains("'bogus'")), rejections.toString());
        }
    }

    private static byte[] sync(String name, int amount) {
        return Sync.newBuilder().setName(name)
                .addVariables(Variable.newBuilder().setName("amount").setValue(amount)).build().toByteArray();
    }
}
