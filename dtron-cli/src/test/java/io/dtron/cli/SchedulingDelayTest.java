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
        assertEquals(Optional.empty(), SchedulingDelay.of(1000).narrowInputWindow(lightContr, ti, 1000, "--virtual-time"));
        // a loaded machine that wakes the tester up to a second late needs windows of 2 s
        String warning = SchedulingDelay.of(1_000_000).narrowInputWindow(lightContr, ti, 1000, "--virtual-time").orElseThrow();
        assertTrue(warning.startsWith("the window of input "), warning);
        assertTrue(warning.contains("narrower than the margin of 2000000 us that inputs need here: they are aimed at"
                + " the window's start and may still come late (INCONCLUSIVE, input executed too late); a time unit of"
                + " at least "), warning);
    }
}
