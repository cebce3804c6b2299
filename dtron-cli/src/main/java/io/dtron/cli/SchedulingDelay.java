package io.dtron.cli;

import io.dtron.engine.ObservableWindow;
import io.dtron.engine.SchedulingLateness;
import io.dtron.engine.TestOptions;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.PrintWriter;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Optional;
import java.util.function.Consumer;
import java.util.function.Predicate;
import java.util.function.ToLongFunction;

/**
 * How late this machine wakes the tester's thread, measured before a real-time run the way the tester waits
 * ({@link SchedulingLateness}), and the input margin that lateness needs: an input is aimed that far inside the end of its
 * window, so that the tester never picks a time it cannot meet.
 *
 * @param worstMicros the latest wake-up measured, in microseconds
 * @param marginMicros the input margin: twice the worst lateness, and never less than {@link
 *                     TestOptions#DEFAULT_INPUT_MARGIN_MICROS}
 */
record SchedulingDelay(long worstMicros, long marginMicros) {
    /** Measures as {@link SchedulingLateness#measureMicros()} does, about 160 ms of waits as the tester waits. */
    static SchedulingDelay measure() {
        return of(SchedulingLateness.measureMicros());
    }

    /**
     * Measures while the engine warms up on {@code network} on another thread ({@link EngineWarmUp}), as a cold JVM
     * compiles and collects when a run starts; returns when both are done (about 300 ms). In dtron's own JVM the
     * compiling is C1's alone from here ({@link RealTimeJit}).
     */
    static SchedulingDelay measureWarmingUp(Network network, TestInterface testInterface) {
        RealTimeJit.compileQuickly();
        Thread warmUp = new Thread(() -> EngineWarmUp.run(network, testInterface), "dtron-warm-up");
        warmUp.setDaemon(true);
        warmUp.start();
        SchedulingDelay delay = measure();
        try {
            warmUp.join();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        return delay;
    }

    /**
     * Before a real-time run of {@code dtron COMMAND}: measures while the engine warms up ({@link
     * #measureWarmingUp}), says what it measured to {@code said} (null: quiet), warns on {@code err} when the
     * model's narrowest input window is narrower than the margin ({@link #narrowInputWindow}), and returns the input
     * margin.
     */
    static long inputMarginForRun(String command, Network network, TestInterface testInterface, long unitMicros,
            String virtualTimeOption, Consumer<String> said, PrintWriter err) {
        SchedulingDelay delay = measureWarmingUp(network, testInterface);
        if (said != null) {
            said.accept("dtron " + command + ": " + delay.describe(unitMicros));
        }
        delay.narrowInputWindow(network, testInterface, unitMicros, virtualTimeOption, channel -> 0, channel -> false)
                .ifPresent(warning -> {
                    err.println("dtron " + command + ": warning: " + warning);
                    err.flush();
                });
        return delay.marginMicros();
    }

    /** What was measured and what inputs are aimed at, for a run at {@code unitMicros} per time unit. */
    String describe(long unitMicros) {
        return String.format(Locale.ROOT, "the tester's thread wakes up to %.3f ms late here; inputs are aimed at"
                + " least %.3f ms (%.3f time units) inside the end of their windows", worstMicros / 1000.0,
                marginMicros / 1000.0, marginMicros / (double) unitMicros);
    }

    /** The margin for a measured worst lateness. */
    static SchedulingDelay of(long worstMicros) {
        long worst = Math.max(0, worstMicros);
        return new SchedulingDelay(worst, SchedulingLateness.inputMarginMicros(worst));
    }

    /**
     * A warning when an input channel's narrowest window ({@link ObservableWindow#narrowest}) at {@code unitMicros} per
     * time unit is narrower than the room its inputs need: this margin plus {@code inputDelayMicros} of the channel
     * (its way to the system, by name; 0 in the tester's process). Inputs in such a window are aimed at its start and
     * may still come late. For an input sent ahead of its time ({@code sentAhead}, its adapter holding it until then)
     * the channel's {@code inputDelayMicros} is how late after its time the adapter applied such inputs. Names each
     * such channel with its figures. {@code virtualTimeOption} is the option that runs in virtual time instead.
     */
    Optional<String> narrowInputWindow(Network network, TestInterface testInterface, long unitMicros,
            String virtualTimeOption, ToLongFunction<String> inputDelayMicros, Predicate<String> sentAhead) {
        List<String> narrow = new ArrayList<>();
        for (TestInterface.ObservableChannel input : testInterface.inputs()) {
            TestInterface one = new TestInterface(List.of(input), List.of(), testInterface.timeUnitMicros(),
                    testInterface.timeout());
            long delay = Math.max(0, inputDelayMicros.applyAsLong(input.name()));
            boolean ahead = sentAhead.test(input.name());
            long room = marginMicros + delay;
            ObservableWindow.narrowest(network, one).filter(w -> w.width() * unitMicros < room).ifPresent(w ->
                    narrow.add("the window of input " + w + " is " + w.width() + " time units of " + unitMicros
                            + " us, narrower than the " + (delay == 0 ? "margin of " + room + " us that inputs need"
                            + " here" : "room of " + room + " us that its inputs need here (a margin of "
                            + marginMicros + " us for the tester's lateness and " + delay + (ahead ? " us for how"
                            + " late after their time the adapter applied them, sent ahead of it)" : " us for their way"
                            + " to the adapter)")) + (w.width() == 0 ? "" : "; a time unit of at least "
                            + ceilDiv(room, w.width()) + " us leaves room")));
        }
        if (narrow.isEmpty()) {
            return Optional.empty();
        }
        boolean instant = narrow.stream().anyMatch(n -> n.contains(" is 0 time units"));
        return Optional.of(String.join("; ", narrow) + ": inputs in such a window are aimed at its start and may"
                + " still come late (INCONCLUSIVE, input executed too late)" + (instant ? "; a single instant cannot"
                + " be met in real time: run the model in virtual time (" + virtualTimeOption + ")" : ""));
    }

    private static long ceilDiv(long a, long b) {
        return -Math.floorDiv(-a, b);
    }
}
