package io.dtron.api;

import io.dtron.api.internal.TesterSide;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.Waits;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.TimeUnit;
import java.util.function.Predicate;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * The channel-serving handshake: a member's listeners and declared outputs reach a tester, whether the member
 * joined before or after it, and changes and departures are seen.
 */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class ChannelHandshakeTest {
    private static final IDtronChannel RESET = IDtronChannel.of("reset");
    private static final IDtronChannel TICK = IDtronChannel.of("tick", "seq");

    private static DtronListener ignoring(IDtronChannel channel) {
        return new DtronListener(channel) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
            }
        };
    }

    /** Waits until the tester's view of the members' channels fits. */
    private static Map<String, ServedChannels> awaitServed(Dtron tester, Predicate<Map<String, ServedChannels>> fits) {
        return Waits.await("the tester's view of the served channels")
                .until(TesterSide.of(tester)::getMembersServedChannels, fits::test);
    }

    @Test
    void aMemberThatJoinedBeforeTheTesterTellsItWhenGreeted() throws Exception {
        String cluster = TestClusters.uniqueName("serve");
        try (Dtron adapter = Dtron.connect(TestClusters.inJvm(cluster).memberName("adapter").build())) {
            adapter.addDtronListener(ignoring(RESET));
            adapter.declareOutputs(TICK);
            assertEquals(new ServedChannels("adapter", Set.of("reset"), Set.of("tick")), adapter.getServedChannels());
            try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build())) {
                Map<String, ServedChannels> served = awaitServed(tester, m -> m.containsKey("adapter"));
                assertEquals(Map.of("adapter", new ServedChannels("adapter", Set.of("reset"), Set.of("tick"))),
                        served);
                // a tester takes part too: it tests what its listeners and its sends say (nothing here), and says
                // that it is a tester
                assertEquals(Map.of("tester", new ServedChannels("tester", Set.of(), Set.of(), false, true)),
                        awaitServed(adapter, m -> m.containsKey("tester")));
                assertEquals(Set.of("tester"), TesterSide.of(adapter).getOtherTesters());
            }
            // known after it left, for a tester deciding whether a member that left served its run
            assertTrue(TesterSide.of(adapter).wasTester("tester"));
            assertFalse(TesterSide.of(adapter).wasTester("adapter"));
        }
    }

    @Test
    void changesAndDeparturesReachTheTester() throws Exception {
        String cluster = TestClusters.uniqueName("serve");
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build())) {
            try (Dtron adapter = Dtron.connect(TestClusters.inJvm(cluster).memberName("adapter").build())) {
                DtronListener reset = ignoring(RESET);
                adapter.addDtronListener(reset);
                awaitServed(tester, m -> Optional.ofNullable(m.get("adapter"))
                        .map(s -> s.receives().equals(Set.of("reset"))).orElse(false));
                // sending on a channel serves it too
                tester.addDtronListener(ignoring(TICK));
                adapter.send(TICK.constructValued(Map.of("seq", 1)));
                awaitServed(tester, m -> m.get("adapter").sends().equals(Set.of("tick")));
                adapter.removeDtronListener(reset);
                ServedChannels last = awaitServed(tester, m -> m.get("adapter").receives().isEmpty()).get("adapter");
                assertEquals(Set.of("tick"), last.sends());
            }
            awaitServed(tester, Map::isEmpty);
        }
    }

    @Test
    void aChannelAMemberStartsSendingOnIsAnnouncedBeforeItsFirstMessageInTheListenersOrder() throws Exception {
        String cluster = TestClusters.uniqueName("serve");
        List<String> seen = Collections.synchronizedList(new ArrayList<>());
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build())) {
            tester.addDtronListener(new DtronListener(TICK) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    seen.add("tick from " + message.getSender());
                }
            });
            TesterSide.of(tester).addServedChannelsListener(served -> seen.add("served "
                    + Optional.ofNullable(served.get("adapter"))
                    .map(s -> s.sends().toString()).orElse("nothing")));
            try (Dtron adapter = Dtron.connect(TestClusters.inJvm(cluster).memberName("adapter").build())) {
                // not declared: sending on tick serves it, and the bus orders the announcement first
                adapter.send(TICK.constructValued(Map.of("seq", 1)));
                Waits.await("the tick").until(() -> seen.contains("tick from adapter"));
            }
            Waits.await("the adapter gone").until(() -> seen.get(seen.size() - 1).equals("served nothing"));
            synchronized (seen) {
                int tick = seen.indexOf("tick from adapter");
                assertTrue(tick > 0 && seen.get(tick - 1).equals("served [tick]"), seen.toString());
                assertEquals("served nothing", seen.get(seen.size() - 1), "the member left after its tick: " + seen);
            }
        }
    }

    @Test
    void aTesterJoiningARunSaysSo() throws Exception {
        String cluster = TestClusters.uniqueName("serve");
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
                Dtron joining = Dtron.connect(TestClusters.inJvm(cluster).memberName("joining").build())) {
            joining.declareOutputs(TICK);
            TesterSide.of(joining).setJoiningRun(true);
            assertTrue(awaitServed(tester, m -> m.containsKey("joining") && m.get("joining").joinsRun())
                    .get("joining").sends().contains("tick"));
            TesterSide.of(joining).setJoiningRun(false);
            awaitServed(tester, m -> !m.get("joining").joinsRun());
        }
    }

    @Test
    void aListenerThatOnlyObservesServesNothingAndTheAlarmChannelIsReserved() throws Exception {
        String cluster = TestClusters.uniqueName("serve");
        try (Dtron tester = Dtron.connect(TestClusters.inJvm(cluster).memberName("tester").tester(true).build());
                Dtron monitor = Dtron.connect(TestClusters.inJvm(cluster).memberName("monitor").build())) {
            monitor.addDtronListener(new DtronListener(TICK) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                }

                @Override
                protected boolean serves() {
                    return false;
                }
            });
            monitor.declareOutputs(RESET); // what it says next reaches the tester after the listener was added
            assertEquals(new ServedChannels("monitor", Set.of(), Set.of("reset")), awaitServed(tester,
                    m -> m.containsKey("monitor") && !m.get("monitor").sends().isEmpty()).get("monitor"));
            assertTrue(Dtron.isReservedChannel("dtron_alarm"));
            assertThrows(IllegalArgumentException.class, () -> monitor.declareOutputs(Dtron.ALARM));
            assertThrows(IllegalArgumentException.class, () -> DtronOptions.builder().channels(List.of(Dtron.ALARM)));
        }
    }

    @Test
    void dtronsOwnChannelsAreNotServed() {
        String cluster = TestClusters.uniqueName("serve");
        try (Dtron adapter = Dtron.connect(TestClusters.inJvm(cluster).memberName("adapter").build())) {
            adapter.addDtronListener(ignoring(Dtron.RUN_START));
            assertFalse(adapter.getServedChannels().receives().contains("dtron_start"));
            assertThrows(IllegalArgumentException.class, () -> adapter.declareOutputs(Dtron.RUN_STOP));
            assertTrue(Dtron.isReservedChannel("dtron_serve"));
        }
    }
}
