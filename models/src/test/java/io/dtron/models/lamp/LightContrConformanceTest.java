package io.dtron.models.lamp;

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
import java.nio.file.Path;
import java.util.stream.LongStream;
import java.util.stream.Stream;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.Arguments;
import org.junit.jupiter.params.provider.MethodSource;

/**
 * Uppaal TRON's smart-lamp case, judged by DTRON's engine in virtual time: the correct lamp passes and every
 * faulty lamp fails, with the explanation its fault calls for, for 20 seeds each.
 */
class LightContrConformanceTest {
    private static Network network;
    private static TestInterface testInterface;

    @BeforeAll
    static void load() throws ModelException {
        Path tron = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        network = ModelLoader.load(tron.resolve("LightContr.xml"));
        testInterface = TestInterface.fromFile(network, tron.resolve("LightContr.trn"));
    }

    static Stream<Arguments> runs() {
        return Stream.of("correct", "late", "early", "wrong-level", "missing")
                .flatMap(v -> LongStream.rangeClosed(1, 20).mapToObj(seed -> Arguments.of(v, seed)));
    }

    @ParameterizedTest(name = "{0}, seed {1}")
    @MethodSource("runs")
    void theCorrectLampPassesAndEveryFaultyLampFails(String variant, long seed) {
        TestOptions options = TestOptions.defaults(seed).withTimeUnit(testInterface.timeUnitMicros())
                .withTimeout(testInterface.timeout());
        TestResult r = new OnlineTester(network, testInterface, new SmartLamp(variant), options).run();
        String why = r.verdict() + ": " + r.explanation();
        switch (variant) {
            case "correct" -> {
                assertEquals(Verdict.PASSED, r.verdict(), why);
                assertTrue(r.inputs() >= 2 && r.outputs() >= 1, r.toString());
            }
            case "late", "missing" -> {
                assertEquals(Verdict.FAILED, r.verdict(), why);
                assertTrue(r.explanation().startsWith("no output came by t="), why);
                assertTrue(r.explanation().contains("The model allowed these outputs: level between t="), why);
                assertTrue(r.explanation().contains("(levelAdapter: _id29 -> _id28)"), why);
            }
            case "early" -> {
                assertEquals(Verdict.FAILED, r.verdict(), why);
                assertTrue(r.explanation().matches("output level\\(adapLevel=\\d+\\) observed at t=[0-9.]+ is not"
                        + " allowed then \\(too early\\)\\..*"), why);
            }
            case "wrong-level" -> {
                assertEquals(Verdict.FAILED, r.verdict(), why);
                assertTrue(r.explanation().matches("output level\\(adapLevel=(\\d+)\\) observed at t=[0-9.]+ carries"
                        + " values the model does not allow then: it allowed level\\(adapLevel=\\d+\\).*"), why);
            }
            default -> throw new IllegalArgumentException(variant);
        }
        assertEquals(seed, r.seed());
    }
}
