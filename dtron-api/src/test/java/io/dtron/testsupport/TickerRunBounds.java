package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * What a PASSED real-time run of the bundled ticker model ({@code models/.../ticker.xml}: a tick 8 to 12 units after
 * the last tick or reset, resets at least R = 25 units apart) guarantees about what {@code dtron run} prints on the
 * bus. How many events a real-time
 * run squeezes in before its timeout is the machine's business (an input due right at the end comes in time or
 * not), so only the model's bounds are asserted.
 */
public final class TickerRunBounds {
    private TickerRunBounds() {
    }

    /**
     * Asserts that the run PASSED at its timeout of {@code timeoutUnits} with as many inputs and outputs as the
     * model allows and a summary that fits them, and returns the number of inputs. The bounds: resets are at least
     * 25 units apart, so at most timeout / 25, and eager resets start at 25; before each reset at least 25 units
     * passed, in which the invariant x <= 12 forced at least 2 ticks; ticks are at least 8 units apart (or after a
     * reset), so at most timeout / 8.
     */
    public static int assertPassed(String out, int timeoutUnits) {
        Matcher passed = Pattern.compile("PASSED: the timeout of " + timeoutUnits + " time units was reached after"
                + " (\\d+) inputs? and (\\d+) outputs?").matcher(out);
        assertTrue(passed.find(), out);
        int inputs = Integer.parseInt(passed.group(1));
        int outputs = Integer.parseInt(passed.group(2));
        assertTrue(inputs >= 1 && inputs <= timeoutUnits / 25, "resets at least 25 units apart: " + out);
        assertTrue(outputs >= 2 * inputs && outputs >= 1 && outputs <= timeoutUnits / 8,
                "ticks within the model's bounds: " + out);
        assertTrue(Pattern.compile("statistics: \\d+ PASSED " + inputs + " " + outputs + " ").matcher(out).find(), out);
        // every judged output was received, so counted; outputs that came as the run ended may add to the count
        Matcher latency = Pattern.compile("latency t2 - t1 of outputs: count (\\d+), min ").matcher(out);
        assertTrue(latency.find() && Long.parseLong(latency.group(1)) >= outputs, out);
        // the tester published the run's start and stop and every input; it accepted at least the outputs it judged
        Matcher bus = Pattern.compile("bus: published (\\d+), accepted (\\d+), rejected ").matcher(out);
        assertTrue(bus.find(), out);
        assertEquals(inputs + 2, Integer.parseInt(bus.group(1)), out);
        assertTrue(Integer.parseInt(bus.group(2)) >= outputs, out);
        return inputs;
    }

    /**
     * Asserts that a run against the slow ticker (a tick every 13 units) FAILED on its first tick, observed at 13 by
     * its run clock or later (when the machine is busy; never earlier), outside the window the model allowed.
     */
    public static void assertSlowTickerFailed(String out) {
        Matcher late = Pattern.compile("FAILED: output tick\\(seq=1\\) observed at t=(\\d+)\\.").matcher(out);
        assertTrue(late.find() && Integer.parseInt(late.group(1)) >= 12, out);
        assertTrue(out.contains("is too late: The model allowed these outputs: tick between t=8.000 and t=12.000"),
                out);
    }
}
