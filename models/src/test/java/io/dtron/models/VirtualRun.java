package io.dtron.models;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.List;

/**
 * A deterministic stand-in for the engine in tests: starts a system under test on a {@link VirtualClock},
 * applies inputs at given model times and records the outputs it reports with their times. Inputs and outputs
 * are checked against the model's test interface (channel and variable names).
 */
public final class VirtualRun implements AdapterContext {

    /** An output and the virtual time, in microseconds, it was reported at. */
    public record Output(long micros, Event event) {
        @Override
        public String toString() {
            return event + "@" + micros + "us";
        }
    }

    private final Adapter system;
    private final TestInterface testInterface;
    private final long timeUnitMicros;
    private final VirtualClock clock = new VirtualClock();
    private final List<Output> outputs = new ArrayList<>();

    /** Starts {@code system} at time 0. */
    public VirtualRun(Adapter system, TestInterface testInterface, long timeUnitMicros) {
        this.system = system;
        this.testInterface = testInterface;
        this.timeUnitMicros = timeUnitMicros;
        system.start(this);
    }

    /** Lets time pass up to {@code units} model time units, then applies {@code input}. */
    public void input(long units, Event input) {
        TestInterface.ObservableChannel channel = testInterface.input(input.channel()).orElseThrow(
                () -> new AssertionError("the model has no input " + input.channel()));
        checkVariables(channel, input);
        runUntil(units);
        system.perform(input);
    }

    /** Lets time pass up to {@code units} model time units. */
    public void runUntil(long units) {
        clock.advanceTo(units * timeUnitMicros);
    }

    /** Stops the system, as the engine does at the end of a run. */
    public void stop() {
        system.stop();
    }

    /** The outputs so far, in the order they were reported. */
    public List<Output> outputs() {
        return List.copyOf(outputs);
    }

    /** An output at {@code units} model time units, to compare with {@link #outputs()}. */
    public Output at(long units, Event event) {
        return new Output(units * timeUnitMicros, event);
    }

    @Override
    public void inconclusive(String reason) {
        throw new AssertionError("the sample system gave up: " + reason);
    }

    @Override
    public void report(Event output) {
        report(output, clock.nowMicros());
    }

    @Override
    public void report(Event output, long eventMicros) {
        TestInterface.ObservableChannel channel = testInterface.output(output.channel()).orElseThrow(
                () -> new AssertionError("the model has no output " + output.channel()));
        checkVariables(channel, output);
        outputs.add(new Output(eventMicros, output));
    }

    @Override
    public void inputApplied(long ordinal, long eventMicros) {
        throw new AssertionError("the sample systems apply their inputs when they are performed");
    }

    @Override
    public VirtualClock clock() {
        return clock;
    }

    @Override
    public TestInterface testInterface() {
        return testInterface;
    }

    @Override
    public long timeUnitMicros() {
        return timeUnitMicros;
    }

    private static void checkVariables(TestInterface.ObservableChannel channel, Event event) {
        List<String> expected = channel.variables().stream().map(TestInterface.AttachedVariable::name).toList();
        if (!expected.equals(List.copyOf(event.values().keySet()))) {
            throw new AssertionError(event + " does not carry the model's variables " + expected);
        }
    }
}
