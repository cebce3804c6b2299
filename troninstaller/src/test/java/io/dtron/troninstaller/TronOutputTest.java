package io.dtron.troninstaller;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Optional;
import java.util.OptionalInt;
import java.util.OptionalLong;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** TRON's output in the format assumed by {@link TronOutput} (see its javadoc): sample texts written for the test. */
@Timeout(value = 10, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronOutputTest {

    @Test
    void verdictExplanationAndSeedFromTheVerdictLine() {
        TronOutput out = TronOutput.parse("""
                UPPAAL TRON 1.5
                Random seed: 1234
                Testing LightContr.xml ...
                TEST FAILED: output level(adapLevel=3) observed at t=71 is too late
                """);
        assertEquals(Optional.of("FAILED"), out.verdict());
        assertEquals(Optional.of("output level(adapLevel=3) observed at t=71 is too late"), out.explanation());
        assertEquals(OptionalLong.of(1234), out.seed());
        assertEquals(OptionalInt.empty(), out.inputs());
    }

    @Test
    void theStatisticsLineGivesSeedVerdictAndCounts() {
        TronOutput out = TronOutput.parse("some banner\n987 INCONCLUSIVE 4 6 310000\n");
        assertEquals(Optional.of("INCONCLUSIVE"), out.verdict());
        assertEquals(OptionalLong.of(987), out.seed());
        assertEquals(OptionalInt.of(4), out.inputs());
        assertEquals(OptionalInt.of(6), out.outputs());
    }

    @Test
    void otherSpellingsOfTheVerdict() {
        assertEquals(Optional.of("PASSED"), TronOutput.parse("Verdict: PASSED\n").verdict());
        assertEquals(Optional.of("PASSED"), TronOutput.parse("Test PASSED\r\n").verdict());
        assertEquals(Optional.of("INCONCLUSIVE"), TronOutput.parse("INCONCLUSIVE: model deadlock").verdict());
        assertEquals(OptionalLong.of(5), TronOutput.parse("dtron tron: m.xml, seed 5, listening").seed());
    }

    @Test
    void noVerdictWhenNonePrinted() {
        TronOutput out = TronOutput.parse("tron: cannot open model.xml\n");
        assertTrue(out.verdict().isEmpty());
        assertTrue(out.seed().isEmpty());
        assertTrue(out.explanation().isEmpty());
    }
}
