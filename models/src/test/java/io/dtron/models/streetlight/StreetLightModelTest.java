package io.dtron.models.streetlight;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/** The street-light model in virtual time, against the application reduced to its result codes. */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class StreetLightModelTest {
    private static final long TIME_UNIT = StreetLightModel.TIME_UNIT_MICROS;

    @Test
    void theInterfaceIsTheSixStepsAndTheResult(@TempDir Path dir) throws Exception {
        TestInterface testInterface = TestInterface.fromNames(ModelLoader.load(StreetLightModel.write(dir, 2)));
        assertEquals(List.of("login[user]", "commandList[user]", "tick[user, controller]", "switch[user, state]",
                "check[user]", "logout[user]"), testInterface.inputs().stream().map(StreetLightModelTest::text)
                .toList());
        assertEquals(List.of("result[user, resCode]"), testInterface.outputs().stream()
                .map(StreetLightModelTest::text).toList());
    }

    @ParameterizedTest(name = "{0} users")
    @ValueSource(ints = {1, 2, 4})
    void theCorrectApplicationPasses(int users, @TempDir Path dir) throws Exception {
        TestResult result = run(dir, users, false, 1);
        assertEquals(Verdict.PASSED, result.verdict(), result.explanation());
        assertTrue(result.inputs() > 20 * users, result.statisticsLine());
    }

    @ParameterizedTest(name = "seed {0}")
    @ValueSource(longs = {1, 2, 3})
    void mixingUpTheUsersFailsOnACheckWithTheCodeTheModelAllowed(long seed, @TempDir Path dir) throws Exception {
        TestResult result = run(dir, 2, true, seed);
        assertEquals(Verdict.FAILED, result.verdict(), result.explanation());
        Matcher m = Pattern.compile("output result\\(user=(\\d), resCode=(\\d+)\\) observed at t=[0-9.]+ carries"
                + " values the model does not allow then: it allowed .*result\\(user=\\1, resCode=(\\d+)\\)")
                .matcher(result.explanation());
        assertTrue(m.find(), result.explanation());
        assertNotEquals(m.group(2), m.group(3), result.explanation());
    }

    private static TestResult run(Path dir, int users, boolean mixUp, long seed) throws Exception {
        Network network = ModelLoader.load(StreetLightModel.write(dir, users));
        TestOptions options = TestOptions.defaults(seed).withTimeUnit(TIME_UNIT).withTimeout(600)
                .withDelayPolicy(DelayPolicy.RANDOM_BOUNDED, 4);
        return new OnlineTester(network, TestInterface.fromNames(network), new SimulatedStreetLights(mixUp), options)
                .run();
    }

    private static String text(TestInterface.ObservableChannel channel) {
        return channel.name() + channel.variables().stream().map(TestInterface.AttachedVariable::name).toList();
    }
}
