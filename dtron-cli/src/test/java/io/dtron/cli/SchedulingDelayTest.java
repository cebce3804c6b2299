package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.TestOptions;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.file.Path;
import java.util.Optional;
import org.junit.jupiter.api.Test;

/** The input margin from the measured scheduling delay, and the warning about input windows narrower than it. */
class SchedulingDelayTest {
    private static final Path TRON = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");

    @Test
    void theMarginIsTwiceTheWorstLatenessAndNeverBelowTheDefault() {
        assertEquals(TestOptions.DEFAULT_INPUT_MARGIN_MICROS, SchedulingDelay.of(300).marginMicros());
        assertEquals(9000, SchedulingDelay.of(4500).marginMicros());
        SchedulingDelay measured = SchedulingDelay.measure();
        assertTrue(measured.worstMicros() >= 0, measured.toString());
        assertEquals(Math.max(TestOptions.DEFAULT_INPUT_MARGIN_MICROS, 2 * measured.worstMicros()),
                measured.marginMicros());
    }

    @Test
    void anInputWindowNarrowerThanTheMarginIsNamedWithATimeUnitThatLeavesRoom() throws Exception {
        Network lightContr = ModelLoader.load(TRON.resolve("LightContr.xml"));
        TestInterface ti = TestInterface.fromFile(lightContr, TRON.resolve("LightContr.trn"));
        // LightContr's narrowest input window is tens of units wide: ample at 1 ms per unit with a 2 ms margin
        assertEquals(Optional.empty(), SchedulingDelay.of(1000).narrowInputWindow(lightContr, ti, 1000, "--virtual-time",
                c -> 0, c -> false));
        // a loaded machine that wakes the tester up to a second late needs windows of 2 s
        String warning = SchedulingDelay.of(1_000_000).narrowInputWindow(lightContr, ti, 1000, "--virtual-time", c -> 0,
                c -> false).orElseThrow();
        assertTrue(warning.startsWith("the window of input "), warning);
        assertTrue(warning.contains("narrower than the margin of 2000000 us that inputs need here; a time unit of at"
                + " least "), warning);
        assertTrue(warning.endsWith(": inputs in such a window are aimed at its start and may still come late"
                + " (INCONCLUSIVE, input executed too late)"), warning);
        // on a bus, the way of the inputs to their adapter adds to the room, per channel
        String bus = SchedulingDelay.of(1000).narrowInputWindow(lightContr, ti, 1000, "--virtual-time",
                c -> c.equals("grasp") ? 150_000 : 0, c -> false).orElseThrow();
        assertTrue(bus.startsWith("the window of input grasp in "), bus);
        assertTrue(bus.contains(" is 100 time units of 1000 us, narrower than the room of 152000 us that its inputs"
                + " need here (a margin of 2000 us for the tester's lateness and 150000 us for their way to the adapter); a"
                + " time unit of at least 1520 us leaves room: inputs"), bus);
        // sent ahead of its time, an input needs room for how late its adapter applied such inputs, not for its way
        String ahead = SchedulingDelay.of(1000).narrowInputWindow(lightContr, ti, 1000, "--virtual-time",
                c -> c.equals("grasp") ? 150_000 : 0, c -> c.equals("grasp")).orElseThrow();
        assertTrue(ahead.contains(" narrower than the room of 152000 us that its inputs need here (a margin of 2000"
                + " us for the tester's lateness and 150000 us for how late after their time the adapter applied"
                + " them, sent ahead of it); a time unit of at least 1520 us leaves room"), ahead);
    }
}
