package io.dtron.bridge;

import io.dtron.api.DtronException;
import io.dtron.api.DtronOptions;
import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.model.TestInterface;
import java.util.Optional;
import java.util.OptionalLong;

/**
 * The tester's engine side of a run on a DTRON bus: the engine's {@link Adapter} for systems under test whose adapters
 * are members of the bus; a controller's plant on the bus too ({@code dtron control --bus}, after {@link
 * BusRunSequence#prepareForControl}). Its {@link BusRun} owns the run (handshake, run id, time 0, clock offsets,
 * event times, reorder window, delays, membership, end); the bridge hands the engine's inputs to it and its questions (is an
 * adapter there, how long an input takes to reach it, when time 0 is) to the run.
 */
public final class BusBridge implements Adapter, AutoCloseable {
    private final BusRun run;

    private BusBridge(BusRun run) {
        this.run = run;
    }

    /**
     * Joins the bus as the tester of a model, which starts its runs (see {@link BusRun#connect}).
     *
     * @throws IllegalArgumentException if the interface's channels cannot travel on the bus
     * @throws DtronException           if the bus cannot be joined
     */
    public static BusBridge connect(TestInterface testInterface, DtronOptions.Builder options) {
        return new BusBridge(BusRun.connect(testInterface, options));
    }

    /**
     * Joins the bus as one tester of a run that another tester starts (see {@link BusRun#join}).
     *
     * @throws IllegalArgumentException if the interface's channels cannot travel on the bus
     * @throws DtronException           if the bus cannot be joined
     */
    public static BusBridge join(TestInterface testInterface, DtronOptions.Builder options) {
        return new BusBridge(BusRun.join(testInterface, options));
    }

    /** Returns the run on the bus this bridge tests in. */
    public BusRun run() {
        return run;
    }

    /** See {@link BusRun#prepare()}. */
    @Override
    public void prepare() {
        run.prepare();
    }

    @Override
    public void start(AdapterContext context) {
        run.start(context);
    }

    @Override
    public void perform(Event input) {
        run.publishInput(input);
    }

    /** See {@link BusRun#publishInput(Event, long)}. */
    @Override
    public void perform(Event input, long dueMicros) {
        run.publishInput(input, dueMicros);
    }

    /** See {@link BusRun#inputLeadMicros(String)}. */
    @Override
    public long inputLeadMicros(String channel) {
        return run.inputLeadMicros(channel);
    }

    /** See {@link BusRun#unreachable()}. */
    @Override
    public Optional<String> unreachable() {
        return run.unreachable();
    }

    /** See {@link BusRun#timeZero()}. */
    @Override
    public OptionalLong timeZero() {
        return run.timeZero();
    }

    /** See {@link BusRun#acknowledgesInputs()}. */
    @Override
    public boolean acknowledgesInputs() {
        return run.acknowledgesInputs();
    }

    /** See {@link BusRun#inputDelayMicros(String)}. */
    @Override
    public long inputDelayMicros(String channel) {
        return run.inputDelayMicros(channel);
    }

    /** See {@link BusRun#stop()}. */
    @Override
    public void stop() {
        run.stop();
    }

    /** See {@link BusRun#stop(long)}. */
    @Override
    public void stop(long observedUntilMicros) {
        run.stop(observedUntilMicros);
    }

    /** Leaves the bus; closing twice does nothing. */
    @Override
    public void close() {
        run.close();
    }
}
