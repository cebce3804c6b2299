package io.dtron.bridge;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.engine.TestOptions;
import io.dtron.model.ModelLoader;
import io.dtron.model.TestInterface;
import io.dtron.testsupport.Waits;
import java.net.InetAddress;
import java.time.Duration;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** {@link BusTest}: a tester's run on a JGroups bus on loopback, prepared from code, with adapters of this JVM. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class BusTestTest {
    private static final String MODEL = """
            chan i_press, o_light;
            process P() { state A; init A; trans A -> A { sync i_press?; }, A -> A { sync o_light!; }; }
            system P;
            """;
    private static final IDtronChannel PRESS = IDtronChannel.of("press");
    private static final IDtronChannel LIGHT = IDtronChannel.of("light");

    private final String cluster = "bustest-" + UUID.randomUUID().toString().substring(0, 8);
    private final Supplier<DtronOptions.Builder> options = () -> DtronOptions.builder().clusterName(cluster)
            .bindAddress(InetAddress.getLoopbackAddress());

    /** An adapter that listens to press and, when {@code light}, says it sends light. */
    private record Lamp(boolean light) implements DtronAdapter {
        @Override
        public void start(Dtron dtron) {
            if (light) {
                dtron.declareOutputs(LIGHT);
            }
            dtron.addDtronListener(new DtronListener(PRESS) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                }
            });
        }
    }

    private static TestInterface testInterface() throws Exception {
        return TestInterface.fromNames(ModelLoader.load("lamp.xta", MODEL));
    }

    @Test
    void theAdaptersJoinAsMembersOfTheirOwnAndTheRunIsPreparedInRealTimeWithAReorderWindow() throws Exception {
        try (BusTest test = BusTest.open(testInterface(), options, List.of(new Lamp(true)), "bus '" + cluster + "'")) {
            assertEquals(2, test.run().members().size(), "the tester and the adapter: " + test.run().members());
            TestOptions prepared = test.prepare(TestOptions.defaults(7).withVirtualTime(true), Duration.ofSeconds(20));
            assertFalse(prepared.virtualTime(), "a run on the bus is in real time");
            assertEquals(7, prepared.seed());
            assertTrue(prepared.reorderWindowMicros() >= BusRun.AUTO_WINDOW_FLOOR_MICROS, prepared.toString());
            assertTrue(prepared.inputMarginMicros() >= TestOptions.DEFAULT_INPUT_MARGIN_MICROS, prepared.toString());
            assertTrue(test.run().unservedChannels().isEmpty());
        }
    }

    @Test
    void aChannelNoAdapterServesIsNamedWithWhatEachMemberServes() throws Exception {
        try (BusTest test = BusTest.open(testInterface(), options, List.of(new Lamp(false)), "bus '" + cluster + "'")) {
            IllegalStateException e = assertThrows(IllegalStateException.class,
                    () -> test.prepare(TestOptions.defaults(1), Duration.ofSeconds(1)));
            assertTrue(e.getMessage().matches("within 1000 ms no adapter on bus '" + cluster + "' served output light;"
                    + " \\S+ receives \\[press\\] and sends \\[\\]"), e.getMessage());
        }
    }

    @Test
    void aSecondTesterOnTheBusRefusesToStartAndLeavesNoAdapterBehind() throws Exception {
        try (BusTest first = BusTest.open(testInterface(), options, List.of(), "bus '" + cluster + "'")) {
            IllegalStateException e = assertThrows(IllegalStateException.class, () -> BusTest.open(testInterface(),
                    options, List.of(new Lamp(true)), "bus '" + cluster + "'"));
            assertEquals("bus '" + cluster + "' has a run in progress: tester " + first.run().memberId() + " is on it,"
                    + " and its adapters would serve both runs; give this run a bus of its own", e.getMessage());
            // the second tester left (its adapter never joined): the bus comes back to the first alone
            Waits.await("the second tester leaves").until(() -> first.run().members().equals(
                    List.of(first.run().memberId())));
        }
    }
}
