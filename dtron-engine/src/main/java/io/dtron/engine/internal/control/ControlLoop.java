package io.dtron.engine.internal.control;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.Steering;
import io.dtron.engine.Strategy;
import io.dtron.engine.TestClock;
import io.dtron.engine.TestOptions;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.control.ControlListener;
import io.dtron.engine.control.ControlPolicy;
import io.dtron.engine.control.ControlResult;
import io.dtron.engine.control.ModelVersion;
import io.dtron.engine.control.SafeAction;
import io.dtron.engine.internal.clock.Reference;
import io.dtron.engine.internal.clock.Ticks;
import io.dtron.engine.internal.clock.RealClock;
import io.dtron.engine.internal.clock.RunClock;
import io.dtron.engine.internal.clock.VirtualClock;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.PartitionException;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.tester.Plan;
import io.dtron.engine.internal.tester.StateSet;
import io.dtron.engine.internal.tester.Steerer;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Random;
import java.util.concurrent.atomic.AtomicReference;

/**
 * One control run (see {@link io.dtron.engine.control.Controller}): the tester's state-set estimation and choice of
 * inputs ({@link Plan}, {@link StateSet}) with the plant's outputs as readings and in-order events; a deviation is an
 * alarm, followed by the safe action. Runs on the caller's thread.
 */
public final class ControlLoop {

    private final Adapter plant;
    private final TestOptions options;
    private final ControlPolicy policy;
    private final List<String> goals;
    private final SafeAction safeAction;
    private final List<ControlListener> listeners;
    private final AtomicReference<ModelVersion> offered;
    private final List<String> refused;
    private final TestInterface plantInterface;
    private final long unit;
    private final int ticksPerUnit;
    private final Ticks ticks;
    private final long endMicros;
    private final Random random;
    private final List<String> versions = new ArrayList<>();

    // the version running
    private Network network;
    private TestInterface testInterface;
    private Semantics semantics;
    private Partition partition;
    private Steerer steerer;
    private TestInterface.ObservableChannel safe;
    private SymState initial;

    private RunClock clock;
    private StateSet set;
    /** The time of the last event, for the order of events. */
    private long lastMicros;
    /**
     * The time of {@link #set}, from which its elapsed clock counts: the start of the tick interval of the last
     * event, on the ticks of the run's start, so that the set keeps when in that interval the event came and no
     * rounding adds up from event to event (as the tester keeps it).
     */
    private Reference reference;
    private int commands;
    private int readings;
    private long instantMicros = -1;
    private int commandsAtInstant;
    private long inputMargin;

    /** A run of {@code network} against {@code plant}; see {@link io.dtron.engine.control.Controller}. */
    public ControlLoop(Network network, TestInterface testInterface, Adapter plant, TestOptions options,
                       ControlPolicy policy, List<String> goals, SafeAction safeAction, List<ControlListener> listeners,
                       AtomicReference<ModelVersion> offered, List<String> refused) {
        this.network = Objects.requireNonNull(network, "network");
        this.testInterface = Objects.requireNonNull(testInterface, "testInterface");
        this.plantInterface = testInterface;
        this.plant = Objects.requireNonNull(plant, "plant");
        this.options = Objects.requireNonNull(options, "options");
        this.policy = policy;
        this.goals = goals;
        this.safeAction = safeAction;
        this.listeners = listeners;
        this.offered = offered;
        this.refused = refused;
        this.unit = options.timeUnitMicros();
        this.ticks = Ticks.of(unit);
        this.ticksPerUnit = ticks.perUnit();
        this.endMicros = Math.multiplyExact(options.timeout(), unit);
        this.random = new Random(options.seed());
    }

    /** Runs to the end of the duration, an alarm, or what stops it. */
    public ControlResult run() {
        use(network, testInterface);
        clock = options.virtualTime() ? new VirtualClock() : new RealClock();
        inputMargin = options.virtualTime() ? 0 : ticks.ceil(options.inputMarginMicros());
        reference = Reference.at(ticks, 0);
        plan(); // once before time starts, so that a cold start does not eat real time
        plant.prepare();
        clock.begin(plant.timeZero());
        plant.start(new Context());
        try {
            return loop();
        } catch (ModelRuntimeException e) {
            return end(ControlResult.Outcome.STOPPED, "model error: " + e.format(), null, -1);
        } finally {
            plant.stop();
        }
    }

    /** Runs {@code model} from its initial state, now. */
    private void use(Network model, TestInterface modelInterface) {
        Partition split;
        try {
            split = Partition.of(model, modelInterface);
        } catch (PartitionException e) {
            throw new UnsupportedModelException(e.getMessage());
        }
        TestInterface.ObservableChannel safeChannel = safeAction.resolve(model, modelInterface).orElse(null);
        Semantics sem = new Semantics(model, ticksPerUnit);
        Steerer steer = policy != ControlPolicy.GOAL ? null : Steerer.of(new Steering(Strategy.GOAL, goals,
                Steering.DEFAULT_HORIZON, -1, false), model, sem, split, List.of());
        network = model;
        testInterface = modelInterface;
        partition = split;
        semantics = sem;
        steerer = steer;
        safe = safeChannel;
        initial = sem.initial();
        set = StateSet.initial(sem, split);
    }

    private ControlResult loop() {
        while (true) {
            long now = clock.nowMicros();
            takeOffered(now);
            if (now >= endMicros) {
                RunClock.TimedEvent last = clock.drain();
                if (last == null) {
                    return end(ControlResult.Outcome.COMPLETED, null, null, -1);
                }
                ControlResult r = receive(last);
                if (r != null) {
                    return r;
                }
                continue;
            }
            if (steerer != null) {
                steerer.check(set, lastMicros, "");
            }
            Plan plan = plan();
            long elapsed = reference.floor(now);
            long lateness = Math.max(inputMargin, ticks.ceil(2 * clock.worstLatenessMicros()));
            Plan.Choice choice = plan.choose(elapsed, random, policy == ControlPolicy.RANDOM
                            ? io.dtron.engine.DelayPolicy.RANDOM : io.dtron.engine.DelayPolicy.EAGER, 0, 0,
                    // commands go at their time: the way they take is room before a window's end, lead included
                    input -> lateness + ticks.ceil(Math.max(0, plant.inputDelayMicros(input.name()))
                            + Math.max(0, plant.inputLeadMicros(input.name()))),
                    earliestCommand(),
                    steerer == null ? null : steerer.scorer());
            long at = reference.micros(choice.ticks());
            boolean deadline = !choice.isInput() && plan.hasDeadline() && choice.ticks() > plan.deadline();
            long target = choice.isInput() || deadline ? at : Math.min(endMicros, at);
            RunClock.TimedEvent event = clock.awaitUntil(target);
            ControlResult r = null;
            if (event != null) {
                r = receive(event);
            } else if (choice.isInput()) {
                RunClock.TimedEvent earlier = clock.drain();
                r = earlier != null ? receive(earlier) : command(choice, plan);
            } else if (deadline) {
                r = missed(choice, plan);
            }
            if (r != null) {
                return r;
            }
        }
    }

    /** Takes the version handed in, if there is one and the run is at a reset point. */
    private void takeOffered(long now) {
        ModelVersion version = offered.get();
        if (version == null || !atResetPoint() || !offered.compareAndSet(version, null)) {
            return;
        }
        try {
            use(version.network(), version.testInterface());
        } catch (RuntimeException e) {
            // the check passed, but the controller cannot run it (its safe action is missing, its goals do not
            // compile): the run goes on with the version it has
            String reason = "it cannot be run: " + e.getMessage();
            refused.add(version.label() + ": " + reason);
            for (ControlListener l : listeners) {
                l.versionRefused(version.label(), reason);
            }
            return;
        }
        lastMicros = now;
        reference = reference.plus(reference.windowStart(now));
        versions.add(version.label() + " at " + time(now));
        for (ControlListener l : listeners) {
            l.versionTaken(version.label(), now);
        }
    }

    /** Whether every state the run may be in is the model's initial state (its locations and values). */
    private boolean atResetPoint() {
        for (SymState s : set.states()) {
            if (!Arrays.equals(s.locations(), initial.locations()) || !Arrays.equals(s.vars(), initial.vars())) {
                return false;
            }
        }
        return !set.isEmpty();
    }

    private Plan plan() {
        return Plan.of(set, semantics, partition, testInterface, unit, reference.ceil(endMicros));
    }

    /** No reading came by the plan's deadline: an alarm, unless the controller itself failed to act. */
    private ControlResult missed(Plan.Choice choice, Plan plan) {
        long deadlineMicros = reference.micros(plan.deadline());
        String deadlineAt = time(deadlineMicros);
        if (choice.letsTimePass() && !plan.environmentLetsTimePass()
                || plan.inputPossibleAt(plan.deadline()) && !choice.letsTimePass()) {
            return end(ControlResult.Outcome.STOPPED, "the controller sent no command by " + deadlineAt + ", when its"
                    + " model required one: it was held up. " + plan.explainInputs(this::time, reference.micros()),
                    null, -1);
        }
        java.util.Optional<String> unreachable = plant.unreachable();
        if (unreachable.isPresent()) {
            return end(ControlResult.Outcome.STOPPED, "no reading came by " + deadlineAt + ", and the plant may not"
                    + " have been able to act: " + unreachable.get(), null, -1);
        }
        // the probe of a plant on the bus flushes what it sent before its answer: a reading still on its way at the
        // deadline is judged at its own time (before the deadline it is taken, after it it is too late)
        RunClock.TimedEvent inTransit = clock.drain();
        if (inTransit != null) {
            return receive(inTransit);
        }
        return alarm("no reading came by " + deadlineAt + ": the model required the plant to act by then. "
                + readings(plan));
    }

    /** The readings {@code plan} allowed and the plant's state, in the controller's terms. */
    private String readings(Plan plan) {
        return plan.explainOutputs(this::time, reference.micros()).replace("The model allowed these outputs:",
                "The model allowed these readings:").replace("The model allowed no outputs then",
                "The model allowed no readings then").replace("the implementation was in", "the plant was in");
    }

    /** Takes what the plant reported; returns the end of the run, or null. */
    private ControlResult receive(RunClock.TimedEvent timed) {
        if (timed.abort() != null) {
            return end(ControlResult.Outcome.STOPPED, timed.abort() + " (at " + time(timed.micros()) + ")", null, -1);
        }
        if (timed.event() == null) {
            return null; // the acknowledgement of a command: events come in order here
        }
        Event event = timed.event();
        long at = Math.max(timed.micros(), lastMicros);
        if (at > endMicros) {
            return null;
        }
        readings++;
        TestInterface.ObservableChannel channel = testInterface.output(event.channel()).orElse(null);
        if (channel == null) {
            return alarm("the plant reported '" + event.channel() + "' at " + time(at) + ", which is no reading of the"
                    + " model");
        }
        List<String> names = channel.variables().stream().map(TestInterface.AttachedVariable::name).toList();
        if (!new java.util.HashSet<>(names).equals(event.values().keySet())) {
            return alarm("the plant reported " + event + " at " + time(at) + ": the model attaches " + names + " to '"
                    + channel.name() + "'");
        }
        Plan before = plan();
        long start = reference.windowStart(at);
        StateSet atTime = set.within(start, reference.ceil(at), null);
        if (atTime.isEmpty()) {
            return alarm("reading " + event + " at " + time(at) + " is too late: " + readings(before));
        }
        List<StateSet.Successor> moves = atTime.successors(channel.channel());
        List<SymState> matching = new ArrayList<>();
        List<StateSet.Successor> taken = new ArrayList<>();
        for (StateSet.Successor s : moves) {
            if (valuesOf(channel, s.state()).equals(event.values())) {
                matching.add(s.state());
                taken.add(s);
            }
        }
        if (!matching.isEmpty()) {
            if (steerer != null) {
                steerer.taken(taken, at, commands, true);
            }
            set = atTime.of(matching);
            lastMicros = at;
            reference = reference.plus(start);
            for (ControlListener l : listeners) {
                l.readingTaken(event, at);
            }
            return null;
        }
        if (!moves.isEmpty()) {
            return alarm("reading " + event + " at " + time(at) + " carries values the model does not allow then");
        }
        String refusal = Plan.environmentRefuses(atTime, semantics, partition, channel.channel());
        if (refusal != null) {
            return alarm("the controller's model cannot take reading " + event + " at " + time(at) + ": " + refusal);
        }
        return alarm("reading " + event + " at " + time(at) + " is not allowed then"
                + before.timing(channel.channel(), reference.floor(at)) + ". "
                + readings(before));
    }

    /** Sends the command chosen, now. */
    private ControlResult command(Plan.Choice choice, Plan plan) {
        long now = clock.quietNow();
        if (now < 0) {
            return null; // a reading came in after the drain: the loop takes it, then plans again
        }
        TestInterface.ObservableChannel channel = choice.input();
        long start = reference.windowStart(now);
        StateSet atTime = set.within(start, reference.ceil(now), null);
        List<StateSet.Successor> moves = atTime.successors(channel.channel());
        if (moves.isEmpty()) {
            return end(ControlResult.Outcome.STOPPED, "command " + channel.name() + " could not be sent at "
                    + time(now) + ": its window had closed (the controller was held up). "
                    + plan.explainInputs(this::time, reference.micros()), null, -1);
        }
        StateSet.Successor chosen = moves.get(random.nextInt(moves.size()));
        Map<String, Integer> values = valuesOf(channel, chosen.state());
        Event event = new Event(channel.name(), values);
        plant.perform(event); // sent first, the bookkeeping after
        List<SymState> next = new ArrayList<>();
        List<StateSet.Successor> taken = new ArrayList<>();
        for (StateSet.Successor s : moves) {
            if (valuesOf(channel, s.state()).equals(values)) {
                next.add(s.state());
                taken.add(s);
            }
        }
        if (steerer != null) {
            steerer.taken(taken, now, commands + 1, false);
        }
        set = atTime.of(next);
        lastMicros = now;
        reference = reference.plus(start);
        commands++;
        countInstant(now);
        for (ControlListener l : listeners) {
            l.commandSent(event, now);
        }
        return null;
    }

    /** Raises the alarm now, takes the safe action if there is one, and ends the run. */
    private ControlResult alarm(String reason) {
        long now = clock.nowMicros();
        for (ControlListener l : listeners) {
            l.alarm(reason, now);
        }
        if (safe == null) {
            return end(ControlResult.Outcome.ALARM, reason + "; the model declares no safe action: the controller"
                    + " stopped", null, now);
        }
        Event command = new Event(safe.name(), valuesOf(safe, set.states().get(0)));
        plant.perform(command);
        commands++;
        for (ControlListener l : listeners) {
            l.safeActionTaken(command, now);
        }
        return end(ControlResult.Outcome.ALARM, reason, command.toString(), now);
    }

    private ControlResult end(ControlResult.Outcome outcome, String reason, String safeTaken, long alarmMicros) {
        return new ControlResult(outcome, reason, options.seed(), commands, readings, alarmMicros < 0 ? 0 : 1,
                alarmMicros, safeTaken, versions, List.copyOf(refused), Math.min(clock.nowMicros(), Math.max(endMicros,
                lastMicros)));
    }

    /**
     * The earliest tick (after the last event) of the next command: 0, or, after {@link
     * OnlineTester#MAX_INPUTS_AT_ONE_INSTANT} commands at one instant, one time unit after it, so that time passes.
     */
    private long earliestCommand() {
        if (commandsAtInstant < OnlineTester.MAX_INPUTS_AT_ONE_INSTANT) {
            return 0;
        }
        return Math.max(1, reference.ceil(instantMicros + unit));
    }

    private void countInstant(long micros) {
        long instant = options.virtualTime() ? 0 : options.inputMarginMicros();
        if (instantMicros >= 0 && micros - instantMicros <= instant) {
            commandsAtInstant++;
        } else {
            instantMicros = micros;
            commandsAtInstant = 1;
        }
    }

    private Map<String, Integer> valuesOf(TestInterface.ObservableChannel channel, SymState state) {
        Map<String, Integer> values = new LinkedHashMap<>();
        for (TestInterface.AttachedVariable v : channel.variables()) {
            values.put(v.name(), state.var(v.variable().offset()));
        }
        return values;
    }

    private String time(long micros) {
        return ticks.time(micros);
    }

    /** The plant's view of the run. */
    private final class Context implements AdapterContext {
        @Override
        public void report(Event output) {
            clock.report(Objects.requireNonNull(output, "output"));
        }

        @Override
        public void report(Event output, long eventMicros) {
            clock.reportAt(Objects.requireNonNull(output, "output"), eventMicros, 0);
        }

        @Override
        public void inputApplied(long ordinal, long eventMicros) {
            // commands are taken where they were sent: the run owner of the bus hands events in order
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
            return plantInterface;
        }

        @Override
        public long timeUnitMicros() {
            return unit;
        }
    }
}
