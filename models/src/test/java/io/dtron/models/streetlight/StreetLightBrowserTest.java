package io.dtron.models.streetlight;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.cli.DtronCommand;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.nio.file.Path;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

/**
 * The street-light application in headless Chromium, one browser per operator, tested against its model by
 * {@code dtron run} on a bus in this JVM, with {@link StreetLightWebTest} as the bus adapter.
 */
@Timeout(value = 150, unit = TimeUnit.SECONDS)
class StreetLightBrowserTest {

    /** The output and exit code of one run. */
    private record Run(int exit, String out) {
    }

    private static Run run(Path dir, int users, String variant, int timeout) throws Exception {
        StringWriter out = new StringWriter();
        StringWriter err = new StringWriter();
        int exit = DtronCommand.run(new String[] {"run", StreetLightModel.write(dir, users).toString(),
                "--adapter", StreetLightWebTest.class.getName() + ":" + variant,
                "--cluster", "streetlight-" + UUID.randomUUID().toString().substring(0, 8),
                "--timeunit", Long.toString(StreetLightModel.TIME_UNIT_MICROS), "--timeout", Integer.toString(timeout),
                "--delay-policy", "random-bounded", "--delay-bound", "4", "--seed", "1"},
                new PrintWriter(out), new PrintWriter(err));
        return new Run(exit, out + "\n" + err);
    }

    /**
     * A correct application never fails. With several operators the model lets the tester send one operator's next
     * input while that operator's last result is still on its way; when the application applies the input after
     * producing the result, and the model does not allow the input after that result, the true order makes the run
     * INCONCLUSIVE (input executed too late), as TRON judges it: allowed, and nothing else.
     */
    @ParameterizedTest(name = "{0} operators for {1} time units")
    @CsvSource({"1, 120", "2, 150", "4, 200"})
    void operatorsAtOnceNeverFailTheCorrectApplication(int users, int timeout, @TempDir Path dir)
            throws Exception {
        Run run = run(dir, users, Integer.toString(users), timeout);
        if (users > 1 && run.exit() == 3) {
            assertTrue(Pattern.compile("\nINCONCLUSIVE: input \\w+\\([^)]*\\) was executed at t=[0-9.]+, when the"
                    + " environment no longer allowed it, after the events that happened before it \\(input executed"
                    + " too late\\)").matcher(run.out()).find(), run.out());
            return;
        }
        assertEquals(0, run.exit(), run.out());
        Matcher passed = Pattern.compile("\nPASSED: the timeout of " + timeout + " time units was reached after"
                + " (\\d+) inputs? and (\\d+) outputs?").matcher(run.out());
        assertTrue(passed.find(), run.out());
        // how many rounds fit is the browser's business (the model gives each answer up to RESPONSE = 10 s); what
        // the model fixes: each operator's inputs and results alternate, the last input's result may be on its way
        int inputs = Integer.parseInt(passed.group(1));
        int outputs = Integer.parseInt(passed.group(2));
        assertTrue(inputs >= 1 && outputs <= inputs && outputs >= inputs - users, run.out());
    }

    @Test
    void theSessionMixUpFailsAMultiUserRunOnAResultCode(@TempDir Path dir) throws Exception {
        Run run = run(dir, 4, "4,mixup", 400);
        assertEquals(2, run.exit(), run.out());
        // after how the tester took the last result, if one came since the last input
        Matcher failed = Pattern.compile("\nFAILED: (?:[^\n]*?; then )?output result\\(user=(\\d), resCode=(\\d+)\\)"
                + " observed at"
                + " t=[0-9.]+ carries values the model does not allow then: it allowed (?:result\\(user=\\d,"
                + " resCode=\\d+\\) or )*result\\(user=\\1, resCode=(\\d+)\\)").matcher(run.out());
        assertTrue(failed.find(), run.out());
        assertNotEquals(failed.group(2), failed.group(3), "observed and expected result codes of operator "
                + failed.group(1) + ": " + run.out());
    }
}
