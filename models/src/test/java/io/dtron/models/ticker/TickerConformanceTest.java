package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/** The bundled Ticker model judges the bundled ticker system: correct passes, slow fails. */
class TickerConformanceTest {

    private static TestResult run(String variant, long seed) throws ModelException {
        Network n = ModelLoader.loadResource(TickerConformanceTest.class.getClassLoader(), "io/dtron/models/ticker.xml");
        return new OnlineTester(n, TestInterface.fromNames(n), new TickerSystem(variant),
                TestOptions.defaults(seed).withTimeout(1000)).run();
    }

    @ParameterizedTest(name = "seed {0}")
    @ValueSource(longs = {1, 2, 3, 4, 5})
    void correctPassesAndSlowFails(long seed) throws ModelException {
        TestResult correct = run("correct", seed);
        assertEquals(Verdict.PASSED, correct.verdict(), correct.explanation());
        assertTrue(correct.outputs() >= 60, correct.toString());
        TestResult slow = run("slow", seed);
        assertEquals(Verdict.FAILED, slow.verdict(), slow.explanation());
        assertTrue(slow.explanation().contains("tick between"), slow.explanation());
    }
}
