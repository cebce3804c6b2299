package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronOptions;
import io.dtron.bridge.BusAdapters;
import io.dtron.bridge.BusBridge;
import io.dtron.bridge.BusRun;
import io.dtron.bridge.BusRunSequence;
import io.dtron.model.TestInterface;
import java.io.PrintWriter;
import java.time.Duration;
import java.util.function.Supplier;
import java.util.Locale;

/**
 * The bus side of {@code dtron run} without {@code --sut}: the tester's {@link BusBridge}, and the bus adapters
 * of {@code --adapter}, each a member of the same bus with a {@link Dtron} of its own. Closing it stops the
 * adapters and leaves the bus.
 */
final class BusSession implements AutoCloseable {
    private final BusBridge bridge;
    private final BusAdapters adapters;

    private BusSession(Supplier<DtronOptions.Builder> options, BusBridge bridge) {
        this.bridge = bridge;
        this.adapters = new BusAdapters(options);
    }

    /**
     * Joins the bus as a tester of the interface, as the tester that starts the run or ({@code joining}) as one that
     * joins a run another tester starts; the adapters of this JVM join with the same options.
     *
     * @throws IllegalArgumentException if the interface's channels cannot travel on the bus
     * @throws io.dtron.api.DtronException if the bus cannot be joined
     */
    static BusSession open(TestInterface testInterface, Supplier<DtronOptions.Builder> options, boolean joining) {
        BusBridge bridge = joining ? BusBridge.join(testInterface, options.get())
                : BusBridge.connect(testInterface, options.get());
        return new BusSession(options, bridge);
    }

    /** The engine's adapter. */
    BusBridge bridge() {
        return bridge;
    }

    /** The run on the bus. */
    BusRun run() {
        return bridge.run();
    }

    /**
     * Connects an adapter of this JVM to the bus as a member of its own and starts it.
     *
     * @return its member id
     * @throws io.dtron.api.DtronException if it cannot join the bus
     */
    String startAdapter(DtronAdapter adapter) {
        return adapters.start(adapter);
    }

    /**
     * Waits until {@code count} members other than the tester are on the bus, then a short while for the last
     * ones to add their listeners (see {@link BusRunSequence#awaitAdapters}).
     *
     * @return whether they came before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    boolean awaitAdapters(int count, Duration timeout) throws InterruptedException {
        return new BusRunSequence(run()).awaitAdapters(count, timeout);
    }

    /**
     * Prints the latency of the messages, the bus counters and, when some came, how many outputs came after the end
     * of the run (they are not judged).
     */
    void printSummary(PrintWriter out) {
        printSummary(bridge.run(), "tester", out);
    }

    /**
     * {@link #printSummary(PrintWriter)} of {@code run}, whose owner (the members' clock offsets are to its clock) is
     * the {@code owner}: the tester, or the controller.
     */
    static void printSummary(BusRun run, String owner, PrintWriter out) {
        out.println("latency t2 - t1 of outputs: " + run.outputLatency());
        out.println("latency t2 - t1 of inputs back from the bus: " + run.inputLatency());
        run.clockOffsets().forEach((member, offset) -> out.printf(Locale.ROOT,
                "clock offset of %s to the %s: %.3f ms +/- %.3f ms%n", member, owner, offset.offsetNanos() / 1e6,
                offset.errorNanos() / 1e6));
        long late = run.outputsAfterEnd();
        long others = run.messagesOfOtherRuns();
        out.println("bus: " + run.stats() + (late == 0 ? "" : ", " + late + " output" + (late == 1 ? "" : "s")
                + " after the end (not judged)") + (others == 0 ? "" : ", " + others + " message"
                + (others == 1 ? "" : "s") + " of other runs (ignored)"));
    }

    @Override
    public void close() {
        adapters.close();
        bridge.close();
    }
}
