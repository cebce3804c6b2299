package io.dtron.engine;

import io.dtron.engine.internal.clock.RealClock;
import io.dtron.engine.internal.clock.RunClock;
import io.dtron.engine.internal.clock.VirtualClock;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.PartitionException;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.tester.Plan;
import io.dtron.engine.internal.tester.StateSet;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Random;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * The online tester: runs a closed Uppaal model against a system under test, as Uppaal TRON does. The
 * environment part of the model chooses inputs and their times; the tester applies them through the
 * {@link Adapter}, observes the outputs the adapter reports with their times, and keeps the set of symbolic
 * states the implementation part of the model may be in. The run ends FAILED when an observation is not
 * allowed (an output, its values or its time) or a required output does not come, INCONCLUSIVE when the
 * environment model cannot accept an output or an input cannot be applied in time, and PASSED when the timeout
 * is reached. Every choice comes from one random source seeded with {@link TestOptions#seed()}; in virtual time
 * the same seed and a deterministic system give the same run.
 */
public final class OnlineTester {
    private static final int MAX_TICKS_PER_UNIT = 1000;

    private final Network network;
    private final TestInterface testInterface;
    private final Adapter adapter;
    private final TestOptions options;
    private final List<TestListener> listeners = new CopyOnWriteArrayList<>();

    /** A tester for {@code network} with the given interface, adapter and options. */
    public OnlineTester(Network network, TestInterface testInterface, Adapter adapter, TestOptions options) {
        this.network = Objects.requireNonNull(network, "network");
        this.testInterface = Objects.requireNonNull(testInterface, "testInterface");
        this.adapter = Objects.requireNonNull(adapter, "adapter");
        this.options = Objects.requireNonNull(options, "options");
    }

    /** Adds a listener that follows the run. */
    public OnlineTester addListener(TestListener listener) {
        listeners.add(Objects.requireNonNull(listener, "listener"));
        return this;
    }

    /**
     * Runs the test to its verdict.
     *
     * @throws UnsupportedModelException when the model uses something the engine cannot run, or its interface
     *                                   does not split it into an environment and an implementation
     */
    public TestResult run() {
        long unit = options.timeUnitMicros();
        int ticksPerUnit = (int) Math.min(unit, MAX_TICKS_PER_UNIT);
        Semantics semantics = new Semantics(network, ticksPerUnit);
        Partition partition;
        try {
            partition = Partition.of(network, testInterface);
        } catch (PartitionException e) {
            throw new UnsupportedModelException(e.getMessage());
        }
        RunClock clock = options.virtualTime() ? new VirtualClock() : new RealClock();
        Run run = new Run(semantics, partition, clock, new Random(options.seed()), ticksPerUnit);
        run.warmUp();
        clock.begin();
        adapter.start(new Context(clock));
        TestResult result;
        try {
            result = run.loop();
        } catch (ModelRuntimeException e) {
            result = run.result(Verdict.INCONCLUSIVE, "model error: " + e.format());
        } finally {
            adapter.stop();
        }
        for (TestListener l : listeners) {
            l.finished(result);
        }
        return result;
    }

    /** The adapter's view of the run. */
    private final class Context implements AdapterContext {
        private final RunClock clock;

        Context(RunClock clock) {
            this.clock = clock;
        }

        @Override
        public void report(Event output) {
            clock.report(Objects.requireNonNull(output, "output"));
        }

        @Override
        public void inconclusive(String reason) {
            clock.abort(Objects.requireNonNull(reason, "reason"));
        }

        @Override
        public TestClock clock() {
            return clock;
        }

        @Override
        public TestInterface testInterface() {
            return testInterface;
        }

        @Override
        public long timeUnitMicros() {
            return options.timeUnitMicros();
        }
    }

    /** One run: its state and its loop. */
    private final class Run {
        private final Semantics semantics;
        private final Partition partition;
        private final RunClock clock;
        private final Random random;
        private final long unit;
        private final int ticksPerUnit;
        private final long timeoutMicros;
        private StateSet set;
        private long lastMicros;
        private int inputs;
        private int outputs;

        Run(Semantics semantics, Partition partition, RunClock clock, Random random, int ticksPerUnit) {
            this.semantics = semantics;
            this.partition = partition;
            this.clock = clock;
            this.random = random;
            this.unit = options.timeUnitMicros();
            this.ticksPerUnit = ticksPerUnit;
            this.timeoutMicros = Math.multiplyExact(options.timeout(), unit);
            this.set = StateSet.initial(semantics, partition);
        }

        /** Plans the first step once before time starts, so that a cold start does not eat real time. */
        void warmUp() {
            Plan.of(set, semantics, partition, testInterface, unit, ticksCeil(timeoutMicros));
        }

        TestResult loop() {
            while (true) {
                long now = clock.nowMicros();
                if (now >= timeoutMicros) {
                    return result(Verdict.PASSED, "the timeout of " + options.timeout() + " time units was reached"
                            + " after " + inputs + " inputs and " + outputs + " outputs, all as the model allows");
                }
                long horizon = ticksCeil(timeoutMicros - lastMicros);
                Plan plan = Plan.of(set, semantics, partition, testInterface, unit, horizon);
                long elapsed = ticksFloor(now - lastMicros);
                Plan.Choice choice = plan.choose(elapsed, random, options.delayPolicy(),
                        options.delayBound() * ticksPerUnit);
                long target = choice.isInput() ? lastMicros + micros(choice.ticks())
                        : Math.min(timeoutMicros, lastMicros + micros(choice.ticks()));
                announceWait(now, target, choice, plan);
                RunClock.TimedEvent output = clock.awaitUntil(target);
                if (output != null) {
                    TestResult verdict = observe(output, plan);
                    if (verdict != null) {
                        return verdict;
                    }
                } else if (clock.nowMicros() >= timeoutMicros && !choice.isInput()) {
                    continue;
                } else if (choice.isInput()) {
                    RunClock.TimedEvent earlier = clock.drain();
                    TestResult verdict = earlier != null ? observe(earlier, plan) : apply(choice, plan);
                    if (verdict != null) {
                        return verdict;
                    }
                } else if (plan.hasDeadline() && choice.ticks() > plan.deadline()) {
                    return result(Verdict.FAILED, "no output came by " + time(lastMicros + micros(plan.deadline()))
                            + ": the model required the system under test to act by then. " + plan.explainOutputs(
                            this::time, lastMicros));
                }
            }
        }

        private void announceWait(long now, long target, Plan.Choice choice, Plan plan) {
            if (listeners.isEmpty()) {
                return;
            }
            TestListener.Until until = choice.isInput() ? TestListener.Until.INPUT
                    : plan.hasDeadline() ? TestListener.Until.OUTPUT_DEADLINE : TestListener.Until.END;
            long untilMicros = until == TestListener.Until.OUTPUT_DEADLINE ? lastMicros + micros(plan.deadline())
                    : target;
            for (TestListener l : listeners) {
                l.waiting(now, untilMicros, until);
            }
        }

        private TestResult observe(RunClock.TimedEvent timed, Plan plan) {
            if (timed.abort() != null) {
                return result(Verdict.INCONCLUSIVE, timed.abort() + " (at " + time(timed.micros()) + ")");
            }
            Event event = timed.event();
            TestInterface.ObservableChannel channel = testInterface.output(event.channel()).orElse(null);
            // a scheduled task that ran late reports at its due time, which may be before the last event seen:
            // the tester has committed to that event, so the output comes after it
            long at = Math.max(timed.micros(), lastMicros);
            if (channel == null) {
                return result(Verdict.INCONCLUSIVE, "the adapter reported '" + event.channel() + "' at " + time(at)
                        + ", which is not an output of the model's interface");
            }
            String badValues = checkNames(channel, event);
            if (badValues != null) {
                return result(Verdict.INCONCLUSIVE, "the adapter reported " + event + " at " + time(at) + ": "
                        + badValues);
            }
            for (TestListener l : listeners) {
                l.outputObserved(event, at);
            }
            outputs++;
            StateSet atTime = set.afterWindow(ticksFloor(at - lastMicros), ticksCeil(at - lastMicros));
            if (atTime.isEmpty()) {
                return result(Verdict.FAILED, "output " + event + " observed at " + time(at) + " is too late: "
                        + plan.explainOutputs(this::time, lastMicros));
            }
            List<StateSet.Successor> moves = atTime.successors(channel.channel());
            List<io.dtron.engine.internal.sem.SymState> matching = new ArrayList<>();
            for (StateSet.Successor s : moves) {
                if (valuesMatch(channel, event, s.state())) {
                    matching.add(s.state());
                }
            }
            if (!matching.isEmpty()) {
                set = atTime.of(matching);
                lastMicros = at;
                return null;
            }
            if (!moves.isEmpty()) {
                return result(Verdict.FAILED, "output " + event + " observed at " + time(at) + " carries values the"
                        + " model does not allow then: it allowed " + allowedValues(channel, moves) + " ("
                        + semantics.describe(moves.get(0).move().steps().get(0)) + ")");
            }
            String envRefusal = Plan.environmentRefuses(atTime, semantics, partition, channel.channel());
            if (envRefusal != null) {
                return result(Verdict.INCONCLUSIVE, "the environment model cannot accept output " + event + " at "
                        + time(at) + ": " + envRefusal);
            }
            return result(Verdict.FAILED, "output " + event + " observed at " + time(at) + " is not allowed then"
                    + plan.timing(channel.channel(), ticksFloor(at - lastMicros)) + ". "
                    + plan.explainOutputs(this::time, lastMicros));
        }

        private TestResult apply(Plan.Choice choice, Plan plan) {
            long now = clock.quietNow();
            if (now < 0) {
                return null; // an output came in after the drain: the loop observes it, then plans again
            }
            long delta = ticksFloor(now - lastMicros);
            TestInterface.ObservableChannel channel = choice.input();
            StateSet atTime = set.afterWindow(delta, ticksCeil(now - lastMicros));
            List<StateSet.Successor> moves = atTime.successors(channel.channel());
            if (moves.isEmpty()) {
                return result(Verdict.INCONCLUSIVE, "input " + channel.name() + " could not be applied at "
                        + time(now) + " (too late for the window the environment allowed). "
                        + plan.explainInputs(this::time, lastMicros));
            }
            StateSet.Successor chosen = moves.get(random.nextInt(moves.size()));
            Map<String, Integer> values = valuesOf(channel, chosen.state());
            List<io.dtron.engine.internal.sem.SymState> next = new ArrayList<>();
            for (StateSet.Successor s : moves) {
                if (valuesOf(channel, s.state()).equals(values)) {
                    next.add(s.state());
                }
            }
            Event event = new Event(channel.name(), values);
            set = atTime.of(next);
            lastMicros = now;
            inputs++;
            for (TestListener l : listeners) {
                l.inputApplied(event, now);
            }
            adapter.perform(event);
            return null;
        }

        private String checkNames(TestInterface.ObservableChannel channel, Event event) {
            List<String> expected = channel.variables().stream().map(TestInterface.AttachedVariable::name).toList();
            if (!new java.util.HashSet<>(expected).equals(event.values().keySet())) {
                return "the interface attaches " + expected + " to '" + channel.name() + "', the event carries "
                        + event.values().keySet();
            }
            return null;
        }

        private boolean valuesMatch(TestInterface.ObservableChannel channel, Event event,
                                    io.dtron.engine.internal.sem.SymState state) {
            for (TestInterface.AttachedVariable v : channel.variables()) {
                if (state.var(v.variable().offset()) != event.value(v.name())) {
                    return false;
                }
            }
            return true;
        }

        private Map<String, Integer> valuesOf(TestInterface.ObservableChannel channel,
                                              io.dtron.engine.internal.sem.SymState state) {
            Map<String, Integer> values = new LinkedHashMap<>();
            for (TestInterface.AttachedVariable v : channel.variables()) {
                values.put(v.name(), state.var(v.variable().offset()));
            }
            return values;
        }

        private String allowedValues(TestInterface.ObservableChannel channel, List<StateSet.Successor> moves) {
            java.util.Set<String> seen = new java.util.LinkedHashSet<>();
            for (StateSet.Successor s : moves) {
                seen.add(new Event(channel.name(), valuesOf(channel, s.state())).toString());
            }
            return String.join(" or ", seen);
        }

        TestResult result(Verdict verdict, String explanation) {
            return new TestResult(verdict, explanation, options.seed(), inputs, outputs, clock.nowMicros());
        }

        private long ticksFloor(long micros) {
            return Math.floorDiv(micros * ticksPerUnit, unit);
        }

        private long ticksCeil(long micros) {
            return -Math.floorDiv(-micros * ticksPerUnit, unit);
        }

        private long micros(long ticks) {
            return -Math.floorDiv(-ticks * unit, ticksPerUnit);
        }

        private String time(long micros) {
            return "t=" + Plan.units(micros, unit);
        }
    }
}
