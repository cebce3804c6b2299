package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testadapter.BusTicker;
import java.time.Duration;
import java.util.concurrent.Callable;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.awaitility.core.ConditionTimeoutException;

/**
 * What a PASSED real-time run of the bundled ticker model ({@code models/.../ticker.xml}: a tick 8 to 12 units after
 * the last tick or reset, resets at least R = 25 units apart) guarantees about what {@code dtron run} prints on the
 * bus. How many events a real-time
 * run squeezes in before its timeout is the machine's business (an input due right at the end comes in time or
 * not), so only the model's bounds are asserted.
 */
public final class TickerRunBounds {
    /** A FAILED verdict on a tick: one that came too late or too early, or none by its deadline. */
    private static final Pattern TICK_FAILED = Pattern.compile("(?m)^FAILED: .*(output tick|no output came by )");
    /**
     * The tester's own words for being held up (as the other pages' runs accept): an input of its came too late, or
     * an event reached it more than the reorder window after it happened, when it had committed to later ones.
     */
    private static final Pattern TESTER_LATE = Pattern.compile("(?m)^INCONCLUSIVE: .*(\\((input executed too late"
            + "|too late for the window the environment allowed)\\)|more than the reorder window)");

    /** What a {@link BusTicker} logs when it was held up past its tolerance. */
    private static final String HELD_UP = "(this JVM was held up)";

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
     * Asserts the verdict of a real-time run of the ticker model against the {@link BusTicker} in this JVM, as it holds
     * whatever the machine's load: PASSED as {@link #assertPassed} says; or FAILED on a tick, and only when the ticker
     * says it was held up past the model's tolerance ({@link BusTicker#heldUpTicks()} grew from {@code heldUpBefore},
     * read before the run): its timer thread fired late, so the system really was late; or INCONCLUSIVE, and only
     * when the tester says that it was held up (its input came too late, or an event reached it later than its
     * reorder window allows). Anything else fails.
     *
     * @return the run's exit code: 0, 2 or 3
     */
    public static int assertPassedUnlessHeldUp(int exit, String out, int timeoutUnits, int heldUpBefore) {
        // the ticker counts a late tick before it publishes it, and an overdue one when it stops at the latest
        return verdictUnlessHeldUp(exit, out, timeoutUnits, () -> BusTicker.heldUpTicks() > heldUpBefore);
    }

    /**
     * Asserts the verdict as {@link #assertPassedUnlessHeldUp(int, String, int, int)} does, of a run against a
     * {@link BusTicker} in another JVM, whose log ({@code tickerLog}, read until it says so or for 10 s) says "(this
     * JVM was held up)" when it was.
     *
     * @return the run's exit code: 0, 2 or 3
     */
    public static int assertPassedUnlessHeldUp(int exit, String out, int timeoutUnits, Callable<String> tickerLog) {
        return verdictUnlessHeldUp(exit, out, timeoutUnits, () -> tickerLog.call().contains(HELD_UP));
    }

    private static int verdictUnlessHeldUp(int exit, String out, int timeoutUnits, Callable<Boolean> heldUp) {
        switch (exit) {
            case 0 -> assertPassed(out, timeoutUnits);
            case 2 -> {
                assertTrue(TICK_FAILED.matcher(out).find(), "FAILED on something else than a tick: " + out);
                try {
                    Waits.await("the ticker to say that it was held up, as the FAILED verdict says it was late")
                            .atMost(Duration.ofSeconds(10)).until(heldUp);
                } catch (ConditionTimeoutException e) {
                    throw new AssertionError("FAILED, yet the ticker kept its period: " + out, e);
                }
            }
            case 3 -> assertTrue(TESTER_LATE.matcher(out).find(),
                    "INCONCLUSIVE for another reason than the tester being held up: " + out);
            default -> throw new AssertionError("exit " + exit + ": " + out);
        }
        return exit;
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
