package io.dtron.models.streetlight;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.models.ticker.LiveMonitorTest;
import java.nio.file.Path;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --cluster NAME} beside live runs of the street-light application in headless Chromium
 * ({@link StreetLightWebTest}, as {@link StreetLightBrowserTest} runs it): no alarm where the correct application
 * PASSED, and the session mix-up's wrong result code found at the result the tester FAILED.
 */
@Timeout(value = 4, unit = TimeUnit.MINUTES)
class StreetLightLiveMonitorTest {
    private static final Pattern VIOLATION = Pattern.compile("(?m)^violation 1 at t=[0-9.]+: (.*)$");

    private static LiveMonitorTest.Result[] run(Path dir, int users, String variant, int timeout) throws Exception {
        String model = StreetLightModel.write(dir, users).toString();
        List<String> bus = List.of("--cluster", "streetlight-" + UUID.randomUUID().toString().substring(0, 8));
        LiveMonitorTest.Command monitor = LiveMonitorTest.monitor(model, bus);
        List<String> args = new java.util.ArrayList<>(List.of("run", model, "--adapter",
                StreetLightWebTest.class.getName() + ":" + variant, "--timeunit",
                Long.toString(StreetLightModel.TIME_UNIT_MICROS), "--timeout", Integer.toString(timeout),
                "--delay-policy", "random-bounded", "--delay-bound", "4", "--seed", "1"));
        args.addAll(bus);
        LiveMonitorTest.Result tester = new LiveMonitorTest.Command(args).get();
        return new LiveMonitorTest.Result[] {tester, monitor.get()};
    }

    @Test
    void theCorrectApplicationRaisesNoAlarm(@TempDir Path dir) throws Exception {
        LiveMonitorTest.Result[] r = run(dir, 2, "2", 150);
        String both = r[1].shown() + r[0].shown();
        if (r[0].exit() == 0) {
            assertEquals(0, r[1].exit(), "the run PASSED, yet:\n" + both);
            assertTrue(r[1].out().contains("no violation"), both);
        }
    }

    @Test
    void theSessionMixUpIsFoundAtTheResultTheTesterFailed(@TempDir Path dir) throws Exception {
        LiveMonitorTest.Result[] r = run(dir, 4, "4,mixup", 400);
        String both = r[1].shown() + r[0].shown();
        assertEquals(2, r[0].exit(), both);
        assertEquals(2, r[1].exit(), both);
        Matcher failed = Pattern.compile("\nFAILED: (?:[^\n]*?; then )?output (result\\(user=\\d, resCode=\\d+\\))"
                + " observed at").matcher(r[0].out());
        assertTrue(failed.find(), both);
        Matcher m = VIOLATION.matcher(r[1].out());
        assertTrue(m.find(), both);
        assertTrue(m.group(1).startsWith(failed.group(1) + " at t="), both);
        assertTrue(m.group(1).contains("carries values the model does not allow then"), both);
    }
}
