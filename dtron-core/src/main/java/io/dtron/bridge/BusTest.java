package io.dtron.bridge;

import io.dtron.api.DtronAdapter;
import io.dtron.api.DtronException;
import io.dtron.api.DtronOptions;
import io.dtron.engine.Adapter;
import io.dtron.engine.SchedulingLateness;
import io.dtron.engine.TestOptions;
import io.dtron.model.TestInterface;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.OptionalLong;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A tester's run on a DTRON bus from code (a test suite's, such as dtron-junit's), prepared as {@code dtron run}
 * prepares one without {@code --sut}: joins the bus as the tester of a model, connects the bus adapters it is given
 * to the bus as members of their own in this JVM, waits until every channel of the model is served, probes the
 * adapters until their round trips are steady and sets the reorder window from the delays measured and the input
 * margin from how late this machine wakes the tester. The engine then tests {@link #adapter()} in real time with the
 * options {@link #prepare} returned. Closing stops the adapters and leaves the bus.
 */
public final class BusTest implements AutoCloseable {
    private static final Logger LOG = LoggerFactory.getLogger(BusTest.class);

    private final BusBridge bridge;
    private final String where;
    private final BusAdapters adapters;

    private BusTest(BusBridge bridge, String where, BusAdapters adapters) {
        this.bridge = bridge;
        this.where = where;
        this.adapters = adapters;
    }

    /**
     * Joins the bus as the tester of {@code testInterface} with the options {@code options} makes, then connects each
     * of {@code adapters} as a member of its own with options it makes too, and starts it.
     *
     * @param where what to call the bus in messages, such as {@code bus 'NAME' on 127.0.0.1}
     * @throws IllegalArgumentException if the interface's channels cannot travel on the bus
     * @throws IllegalStateException    if a tester of another run joined the bus first (its adapters would serve both)
     * @throws DtronException           if the tester or an adapter cannot join the bus
     * @throws InterruptedException     if the thread was interrupted while the members on the bus said who they are
     */
    public static BusTest open(TestInterface testInterface, Supplier<DtronOptions.Builder> options,
            List<? extends DtronAdapter> adapters, String where) throws InterruptedException {
        BusTest test = new BusTest(BusBridge.connect(testInterface, options.get()), where,
                new BusAdapters(options));
        try {
            // before this JVM's adapters join, so that a run that does not start leaves none behind
            List<String> others = test.bridge.run().testersThatJoinedFirst();
            if (!others.isEmpty()) {
                throw new IllegalStateException(where + " has a run in progress: tester " + String.join(", ", others)
                        + " is on it, and its adapters would serve both runs; give this run a bus of its own");
            }
            adapters.forEach(test.adapters::start);
            return test;
        } catch (RuntimeException | InterruptedException e) {
            test.close();
            throw e;
        }
    }

    /**
     * Waits (at most {@code wait}) until every channel of the model is served by an adapter on the bus, checks that
     * each output has one owner, probes the adapters until their round trips are steady while it measures how late
     * this machine wakes the tester ({@link SchedulingLateness}), and returns {@code options} in real time with the
     * reorder window the delays measured call for and the input margin the lateness calls for (or {@code options}'
     * own, when larger).
     *
     * @throws IllegalStateException if a channel is still not served after {@code wait}, naming it and what each
     *                               member serves, or two members send one output
     * @throws InterruptedException  if the thread was interrupted while waiting
     */
    public TestOptions prepare(TestOptions options, Duration wait) throws InterruptedException {
        BusRun run = bridge.run();
        if (!run.awaitChannelsServed(wait)) {
            List<String> parts = new ArrayList<>();
            run.servedChannels().forEach((member, channels) -> parts.add(member + " receives " + channels.receives()
                    + " and sends " + channels.sends()));
            throw new IllegalStateException("within " + wait.toMillis() + " ms no adapter on " + where + " served "
                    + String.join(", ", run.unservedChannels()) + (parts.isEmpty() ? "; no adapter said which"
                    + " channels it serves (members: " + run.members() + ")" : "; " + String.join(", ", parts)));
        }
        run.ownersConflict().ifPresent(conflict -> {
            throw new IllegalStateException(where + ": " + conflict);
        });
        run.expectAdapters();
        // how late this machine wakes the tester, measured while the probes keep it busy, as before dtron run's runs
        long[] lateness = new long[1];
        Thread measuring = new Thread(() -> lateness[0] = SchedulingLateness.measureMicros(), "dtron-lateness");
        measuring.setDaemon(true);
        measuring.start();
        BusRun.Probing probing = run.warmUp(true);
        measuring.join();
        long window = run.reorderWindow(run.measuredDelays(), OptionalLong.empty());
        long margin = Math.max(options.inputMarginMicros(), SchedulingLateness.inputMarginMicros(lateness[0]));
        LOG.info("Probed the adapters {} times in {} ms; the tester wakes up to {} us late here, so inputs are aimed"
                + " {} us inside the end of their windows; reorder window {} us", probing.rounds(), probing.millis(),
                lateness[0], margin, window);
        return options.withVirtualTime(false).withInputMargin(margin).withReorderWindow(window);
    }

    /** The engine's adapter of the run: the systems under test behind the adapters on the bus. */
    public Adapter adapter() {
        return bridge;
    }

    /** The run on the bus. */
    public BusRun run() {
        return bridge.run();
    }

    /** Stops the adapters this test started and leaves the bus; closing twice does nothing more. */
    @Override
    public void close() {
        adapters.close();
        bridge.close();
    }
}
