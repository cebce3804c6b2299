package io.dtron.engine;

import io.dtron.engine.coverage.Goals;
import io.dtron.engine.coverage.RunCoverage;
import io.dtron.engine.coverage.StopCondition;
import io.dtron.engine.internal.clock.Reference;
import io.dtron.engine.internal.clock.Ticks;
import io.dtron.engine.internal.clock.RealClock;
import io.dtron.engine.internal.clock.RunClock;
import io.dtron.engine.internal.clock.VirtualClock;
import io.dtron.engine.internal.coverage.Recorder;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.PartitionException;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.tester.Plan;
import io.dtron.engine.internal.tester.StateSet;
import io.dtron.engine.internal.verify.Coverable;
import io.dtron.engine.internal.verify.ZenoCycles;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Random;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.atomic.AtomicLong;

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
    /**
     * How many reorder windows past its time a held verdict, or the commitment to an input, waits for the
     * acknowledgement of an input, when the adapters acknowledge inputs: its place decides the order of events.
     */
    private static final int ACK_PATIENCE = 4;
    /**
     * The most inputs the tester gives at one instant (in real time: within the input margin of the first): then it
     * lets time pass, its next input at least one model time unit later, so that an environment that may give inputs
     * without time passing (Zeno) does not hold time still, and an output deadline is reached and judged.
     */
    public static final int MAX_INPUTS_AT_ONE_INSTANT = 100;
    /** How long, by default, the model checker looks for what can be covered before a run. */
    public static final java.time.Duration DEFAULT_COVERABLE_BUDGET = java.time.Duration.ofSeconds(2);
    /** The most symbolic states the check of what can be covered stores. */
    private static final long COVERABLE_MAX_STATES = 200_000;

    private final Network network;
    private final TestInterface testInterface;
    private final Adapter adapter;
    private final TestOptions options;
    private final List<TestListener> listeners = new CopyOnWriteArrayList<>();
    private Steering steering;
    private io.dtron.engine.internal.tester.Steerer steerer;
    /** The trap names the steerer was made with: made again when {@link #traps} changed them. */
    private java.util.Set<String> steererTraps;
    private boolean steererUsed;
    private java.time.Duration coverableBudget = DEFAULT_COVERABLE_BUDGET;
    private java.util.Set<String> traps = java.util.Set.of();
    private StopCondition until;
    private Goals goals = Goals.NONE;
    private volatile Recorder recorder;

    /** A tester for {@code network} with the given interface, adapter and options. */
    public OnlineTester(Network network, TestInterface testInterface, Adapter adapter, TestOptions options) {
        this.network = Objects.requireNonNull(network, "network");
        this.testInterface = Objects.requireNonNull(testInterface, "testInterface");
        this.adapter = Objects.requireNonNull(adapter, "adapter");
        this.options = Objects.requireNonNull(options, "options");
    }

    /**
     * Whether the environment of {@code network} may give inputs without end at one instant (Zeno), found as
     * {@code dtron check --testability} finds Zeno cycles, structurally: a cycle of an environment process of sends
     * and internal edges on which no clock is both reset and bounded from below. Returns one line saying which
     * cycle and what the tester does about it, or empty when there is none, or the model cannot be run.
     */
    public static java.util.Optional<String> zenoEnvironment(Network network, TestInterface testInterface) {
        Partition partition;
        int dimension;
        try {
            partition = Partition.of(network, testInterface);
            dimension = new Semantics(network, 1).dimension();
        } catch (PartitionException | UnsupportedModelException e) {
            return java.util.Optional.empty(); // the run says why
        }
        for (int p = 0; p < network.processes().size(); p++) {
            if (!partition.isEnvironment(p)) {
                continue;
            }
            io.dtron.model.Process process = network.processes().get(p);
            List<String> cycle = ZenoCycles.possiblyZenoAlone(process, dimension);
            if (cycle != null) {
                return java.util.Optional.of("the environment may give inputs with no time passing (Zeno): the cycle "
                        + String.join(" -> ", cycle) + " of " + process.name() + " may take no time; the tester gives"
                        + " at most " + MAX_INPUTS_AT_ONE_INSTANT + " inputs at one instant, then lets time pass (its"
                        + " next input at least a time unit later), so that a missed output deadline is reached and"
                        + " judged");
            }
        }
        return java.util.Optional.empty();
    }

    /**
     * Names further trap variables: bool variables or arrays (qualified, {@code Lamp.seen}, or not) counted as traps
     * besides those whose name starts with {@code trap} or {@code t_}.
     */
    public OnlineTester traps(java.util.Collection<String> names) {
        this.traps = java.util.Set.copyOf(names);
        return this;
    }

    /**
     * How long the model checker may look for what can be covered (the reachable locations and edges of the closed
     * network) before the run starts; {@link java.time.Duration#ZERO} for no check (everything counts as
     * coverable). When the budget runs out, the coverage says so and counts what it did not decide as coverable.
     */
    public OnlineTester coverableBudget(java.time.Duration budget) {
        this.coverableBudget = Objects.requireNonNull(budget, "budget");
        return this;
    }

    /**
     * Ends the run PASSED, before its timeout, when {@code condition} holds (checked after every event and at each
     * of its {@code time(T)}), the explanation naming which of its conditions held; {@code goals} answers its
     * {@code reached(N)}. The run checks the condition against the goals and the model's traps when it starts,
     * and throws an {@link IllegalArgumentException} naming the column when they do not fit.
     */
    public OnlineTester until(StopCondition condition, Goals goals) {
        this.until = Objects.requireNonNull(condition, "condition");
        this.goals = Objects.requireNonNull(goals, "goals");
        return this;
    }

    /**
     * The coverage of the run in progress (as far as the tester has committed to its events), or of the last run;
     * null before a run has started. Read it on the tester's thread while the run lasts.
     */
    public RunCoverage coverage() {
        return recorder;
    }

    /** Adds a listener that follows the run. */
    public OnlineTester addListener(TestListener listener) {
        listeners.add(Objects.requireNonNull(listener, "listener"));
        return this;
    }

    /**
     * Steers the run toward test purposes and coverage (see {@link Steering}); before {@link #run}.
     *
     * @throws io.dtron.engine.verify.QueryException when a goal is not an {@code E<>} query or does not compile
     * @throws UnsupportedModelException when the model cannot be run or explored
     */
    public OnlineTester steer(Steering steering) {
        this.steering = Objects.requireNonNull(steering, "steering");
        this.steerer = null;
        steerer();
        return this;
    }

    /**
     * What the steering found: before the run, the goals the model checker proves unreachable (the others open);
     * after it, the goals reached (when) and found unreachable (when, why), and the edges covered. Null without
     * {@link #steer steering}.
     */
    public SteeringReport steeringReport() {
        if (steering == null) {
            return null;
        }
        io.dtron.engine.internal.tester.Steerer s = steerer();
        int[] edges = s.edgeCoverage();
        int[] env = s.environmentCoverage();
        long[] full = s.environmentCovered();
        return new SteeringReport(s.goals(), s.complete(), edges[0], edges[1], env[0], env[1], full[0],
                (int) full[1]);
    }

    /**
     * Whether goal number {@code index} (from 0) of the {@link #steer steering} has been reached so far; false without
     * steering. Answers at once, for a stop condition's {@code reached(N)}.
     */
    public boolean goalReached(int index) {
        io.dtron.engine.internal.tester.Steerer s = steerer;
        return s != null && index >= 0 && index < s.goalCount() && s.reached(index);
    }

    private io.dtron.engine.internal.tester.Steerer steerer() {
        if (steerer == null && steering != null) {
            Partition partition;
            try {
                partition = Partition.of(network, testInterface);
            } catch (PartitionException e) {
                throw new UnsupportedModelException(e.getMessage());
            }
            Semantics semantics = new Semantics(network, ticksPerUnit());
            steererTraps = traps;
            steerer = io.dtron.engine.internal.tester.Steerer.of(steering, network, semantics, partition,
                    io.dtron.engine.coverage.Traps.of(network, traps));
        }
        return steerer;
    }

    private int ticksPerUnit() {
        return Ticks.of(options.timeUnitMicros()).perUnit();
    }

    /**
     * Runs the test to its verdict.
     *
     * @throws UnsupportedModelException when the model uses something the engine cannot run, or its interface
     *                                   does not split it into an environment and an implementation
     */
    public TestResult run() {
        long unit = options.timeUnitMicros();
        int ticksPerUnit = ticksPerUnit();
        Semantics semantics = new Semantics(network, ticksPerUnit);
        Partition partition;
        try {
            partition = Partition.of(network, testInterface);
        } catch (PartitionException e) {
            throw new UnsupportedModelException(e.getMessage());
        }
        io.dtron.engine.coverage.Traps.of(network, traps); // refuses names that are no bool variables
        Coverable coverable;
        try {
            coverable = coverableBudget.isZero() ? Coverable.unchecked(network)
                    : Coverable.cached(network, coverableBudget, COVERABLE_MAX_STATES);
        } catch (ModelRuntimeException e) {
            coverable = Coverable.failed(network, "the check of what can be covered stopped at a model error: "
                    + e.format());
        }
        Recorder coverage = new Recorder(network, partition, testInterface, coverable, options.seed(), traps);
        if (until != null) {
            until.check(goals.count(), coverage.traps().total());
        }
        recorder = coverage;
        RunClock clock = options.virtualTime() ? new VirtualClock() : new RealClock();
        AtomicLong window = new AtomicLong(options.reorderWindowMicros());
        if (steering != null && (steererUsed || !traps.equals(steererTraps))) {
            steerer = null; // a run of its own, with the traps as they are now
        }
        steerer();
        steererUsed = steering != null;
        Run run = new Run(semantics, partition, clock, new Random(options.seed()), ticksPerUnit, window, coverage);
        run.warmUp();
        adapter.prepare();
        clock.begin(adapter.timeZero());
        TestResult result = null;
        try {
            try {
                adapter.start(new Context(clock, window));
            } catch (RuntimeException | AssertionError e) {
                result = run.result(Verdict.INCONCLUSIVE, RunClock.thrown("the system under test", e)
                        + " when it was started");
            }
            if (result == null) {
                result = run.loop();
            }
        } catch (ModelRuntimeException e) {
            result = run.result(Verdict.INCONCLUSIVE, "model error: " + e.format());
        } finally {
            if (result != null) {
                // the tester judged the events up to its end, or up to its verdict when that came first
                adapter.stop(Math.min(result.durationMicros(), run.timeoutMicros));
            } else {
                adapter.stop();
            }
        }
        run.recordPending();
        result = new TestResult(result.verdict(), result.explanation(), result.seed(), result.inputs(),
                result.outputs(), result.durationMicros(), coverage.snapshot());
        for (TestListener l : listeners) {
            l.finished(result);
        }
        return result;
    }

    /** The adapter's view of the run. */
    private final class Context implements AdapterContext {
        private final RunClock clock;
        private final AtomicLong window;

        Context(RunClock clock, AtomicLong window) {
            this.clock = clock;
            this.window = window;
        }

        @Override
        public void report(Event output) {
            clock.report(Objects.requireNonNull(output, "output"));
        }

        @Override
        public void report(Event output, long eventMicros) {
            report(output, eventMicros, 0);
        }

        @Override
        public void report(Event output, long eventMicros, long uncertaintyMicros) {
            if (uncertaintyMicros < 0) {
                throw new IllegalArgumentException("negative uncertainty: " + uncertaintyMicros);
            }
            clock.reportAt(Objects.requireNonNull(output, "output"), eventMicros, uncertaintyMicros);
        }

        @Override
        public void inputApplied(long ordinal, long eventMicros) {
            inputApplied(ordinal, eventMicros, 0);
        }

        @Override
        public void inputApplied(long ordinal, long eventMicros, long uncertaintyMicros) {
            if (ordinal <= 0) {
                throw new IllegalArgumentException("inputs are numbered from 1: " + ordinal);
            }
            if (uncertaintyMicros < 0) {
                throw new IllegalArgumentException("negative uncertainty: " + uncertaintyMicros);
            }
            clock.inputApplied(ordinal, eventMicros, uncertaintyMicros);
        }

        @Override
        public void widenReorderWindow(long micros) {
            if (options.reorderWindowMicros() > 0) {
                window.accumulateAndGet(Math.min(micros, TestOptions.MAX_DURATION_MICROS), Math::max);
            }
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

        @Override
        public long endMicros() {
            return Math.multiplyExact(options.timeout(), options.timeUnitMicros());
        }
    }

    /**
     * An event the tester has seen but not committed to: an earlier-stamped message may still arrive within the
     * reorder window and be placed before it. Kept in time order, each with the state set after it.
     */
    private static final class Pending {
        final Event event;
        final boolean input;
        final long ordinal;
        final long sentMicros;
        long micros;
        /** The event happened within this many microseconds of {@link #micros}: the clocks' error bound. */
        long uncertainty;
        /** For an input: whether the tester performed it ahead of its time, for its adapter to hold until then. */
        boolean ahead;
        /** For an input: whether its adapter acknowledged it. */
        boolean acknowledged;
        /**
         * For an input: whether the model allowed it only within {@link #uncertainty} of where it was applied, not
         * there: it may have come after the environment's window closed.
         */
        boolean doubtful;
        StateSet after;
        /** The time of the last event up to and with this one, and the time of the state set after it. */
        long afterMicros;
        Reference afterReference;
        /** What the event took, once judged allowed; null before, or when a verdict came at or before it. */
        Recorder.Step taken;

        /** How an explanation says when the input left: "sent", or "due" for one performed ahead of its time. */
        String sentOrDue() {
            return ahead ? "due" : "sent";
        }

        Pending(Event event, boolean input, long ordinal, long micros) {
            this.event = event;
            this.input = input;
            this.ordinal = ordinal;
            this.sentMicros = micros;
            this.micros = micros;
        }
    }

    /** A verdict that holds for the order of events seen so far, final once no earlier event can arrive. */
    private record Held(TestResult result, long finalMicros, long eventMicros) {
    }

    /** One run: its state and its loop. */
    private final class Run {
        private final Semantics semantics;
        private final Partition partition;
        private final RunClock clock;
        private final Random random;
        private final long unit;
        private final int ticksPerUnit;
        private final Ticks ticks;
        /** The end of the run: the timeout, or when the stop condition was met. */
        private long timeoutMicros;
        private final Recorder coverage;
        /** What the last event judged allowed took. */
        private Recorder.Step lastStep;
        /** Which conditions of the stop condition held, once it did. */
        private String stoppedBy;
        /** The reorder window in microseconds; widened during the run by the adapter. */
        private final AtomicLong windowMicros;
        /** How far, in ticks, an input is aimed inside the end of its window: a real clock wakes up late. */
        private final long inputMargin;
        /** The state set after every event committed to, at the time of the last of them. */
        private StateSet committed;
        private long committedMicros;
        private Reference committedReference;
        /** The events after those, in time order; {@link #set} is the state after all of them. */
        private final List<Pending> pending = new ArrayList<>();
        /** The committed inputs by number, while their acknowledgements may still come. */
        private final Map<Long, Pending> committedInputs = new LinkedHashMap<>();
        private StateSet set;
        /** The time of the last event. */
        private long lastMicros;
        /**
         * The time of {@link #set}, from which its elapsed clock counts: the start of the last event's window (its
         * time rounded down to a tick, less its clock error), so that the set keeps when in the window the event
         * came, and the reference stays on the ticks of the run's start and no rounding adds up from event to event.
         */
        private Reference reference;
        /** The last plan, and the state set, time and horizon it was made for: reused while they hold. */
        private Plan lastPlan;
        private StateSet lastPlanSet;
        private Reference lastPlanReference;
        private long lastPlanHorizon;
        private Held held;
        /** How the last output observed was understood (the edges it was taken as), until the next input. */
        private String lastTaken;
        /** The last committed input the model allowed only within its clock error ({@link Pending#doubtful}). */
        private Pending doubtCommitted;
        /** How many acknowledgements of inputs came in this run. */
        private long acknowledgements;
        private long performed;
        private int inputs;
        private int outputs;
        /** When the inputs at one instant began, and how many there have been ({@link #MAX_INPUTS_AT_ONE_INSTANT}). */
        private long instantMicros = -1;
        private int inputsAtInstant;

        Run(Semantics semantics, Partition partition, RunClock clock, Random random, int ticksPerUnit,
            AtomicLong windowMicros, Recorder coverage) {
            this.semantics = semantics;
            this.partition = partition;
            this.clock = clock;
            this.random = random;
            this.unit = options.timeUnitMicros();
            this.ticksPerUnit = ticksPerUnit;
            this.ticks = new Ticks(unit, ticksPerUnit);
            this.timeoutMicros = Math.multiplyExact(options.timeout(), unit);
            this.windowMicros = windowMicros;
            this.inputMargin = options.virtualTime() ? 0 : ticks.ceil(options.inputMarginMicros());
            this.set = StateSet.initial(semantics, partition);
            this.committed = set;
            this.reference = Reference.at(ticks, 0);
            this.committedReference = reference;
            this.coverage = coverage;
            coverage.start(set);
        }

        private long window() {
            return windowMicros.get();
        }

        /** Plans the first step once before time starts, so that a cold start does not eat real time. */
        void warmUp() {
            plan();
        }

        private Plan plan() {
            long horizon = reference.ceil(timeoutMicros);
            if (lastPlan == null || lastPlanSet != set || !reference.equals(lastPlanReference)
                    || lastPlanHorizon != horizon) {
                lastPlan = Plan.of(set, semantics, partition, testInterface, unit, horizon);
                lastPlanSet = set;
                lastPlanReference = reference;
                lastPlanHorizon = horizon;
            }
            return lastPlan;
        }

        /**
         * Tells the listeners the window in which the model allowed output {@code event} on {@code channel} at {@code
         * at}, from the plan of the state set after the last event (the tester's plan for its wait, computed again
         * only when that set changed since).
         */
        private void announceWindow(Event event, TestInterface.ObservableChannel channel, long at) {
            if (at < lastMicros || held != null) {
                // it came before an event already judged, or after one whose verdict is held: the set it is judged in
                // is not the current one
                return;
            }
            long[] w = plan().windowAt(channel.channel(), reference.floor(at));
            if (w == null) {
                return;
            }
            long earliest = reference.micros(w[0]);
            long latest = w[1] == Long.MAX_VALUE ? -1 : reference.micros(w[1]);
            for (TestListener l : listeners) {
                l.outputWindow(event, at, earliest, latest);
            }
        }

        /**
         * Whether the plan's output deadline is one the run judges: the tester's wait past it (one tick after it)
         * begins before the run's end.
         */
        private boolean deadlineBeforeTheEnd(Plan plan) {
            return plan.hasDeadline() && reference.micros(plan.deadline() + 1) < timeoutMicros;
        }

        TestResult loop() {
            while (true) {
                long now = clock.nowMicros();
                if (held != null) {
                    long until = held.finalMicros();
                    if (now >= until) {
                        Pending unacknowledged = awaitingAcknowledgement(held.eventMicros());
                        if (unacknowledged == null) {
                            return result(held.result().verdict(), held.result().explanation());
                        }
                        // the verdict depends on where that input was applied, which its acknowledgement will say
                        until = ackDeadline(held.finalMicros());
                        if (now >= until) {
                            return result(Verdict.INCONCLUSIVE, "input " + unacknowledged.event + " was "
                                    + unacknowledged.sentOrDue() + " at " + time(unacknowledged.sentMicros)
                                    + ", but the acknowledgement of when it was applied had not come by " + time(now)
                                    + ", and the verdict depends on it: "
                                    + held.result().verdict() + " if it was applied then (" + held.result()
                                    .explanation() + ")");
                        }
                    }
                    TestResult verdict = receive(clock.awaitUntil(until));
                    if (verdict != null) {
                        return verdict;
                    }
                    continue;
                }
                commit(now - window());
                if (lastMicros > now) {
                    // an input performed ahead is due later: the tester takes up the run at its time, which its
                    // adapter keeps (the tester's own wait need not be precise, and spins none of it)
                    TestResult verdict = receive(clock.awaitLooselyUntil(lastMicros));
                    if (verdict != null) {
                        return verdict;
                    }
                    continue;
                }
                if (until != null && stoppedBy == null && now < timeoutMicros) {
                    stoppedBy = until.met(stopContext(now));
                    if (stoppedBy != null) {
                        timeoutMicros = Math.max(now, lastMicros);
                    }
                }
                // a deadline before the end is judged even when the wait for messages in transit after it (a reorder
                // window widened while the tester waited) took the run past its end
                if (now >= timeoutMicros && !deadlineBeforeTheEnd(plan())) {
                    RunClock.TimedEvent last = now >= timeoutMicros + window() ? clock.drain() : null;
                    if (last != null) {
                        // reported (or due) before the end: judged before the verdict
                        TestResult verdict = receive(last);
                        if (verdict != null) {
                            return verdict;
                        }
                        continue;
                    }
                    if (now >= timeoutMicros + window()) {
                        if (stoppedBy != null) {
                            return result(Verdict.PASSED, "the stop condition " + until + " was met at "
                                    + time(timeoutMicros) + " by " + stoppedBy + ", after " + inputs + " inputs and "
                                    + outputs + " outputs, all as the model allows");
                        }
                        String timedOut = "the timeout of " + options.timeout() + " time units was reached after "
                                + inputs + " inputs and " + outputs + " outputs, all as the model allows";
                        String open = steerer == null ? "" : steerer.openAtTheEnd();
                        if (!open.isEmpty()) {
                            return result(Verdict.INCONCLUSIVE, timedOut + ", but not every goal was reached, so the"
                                    + " run did not serve its purpose: not reached: " + open);
                        }
                        return result(Verdict.PASSED, timedOut);
                    }
                    TestResult verdict = receive(clock.awaitUntil(timeoutMicros + window()));
                    if (verdict != null) {
                        return verdict;
                    }
                    continue;
                }
                TestResult steered = steered(now);
                if (steered != null) {
                    return steered;
                }
                Plan plan = plan();
                long elapsed = reference.floor(now);
                // room before a window's end: for the tester's own lateness (a measure of how late this machine's
                // threads act, an adapter's that keeps an input's time as well), and for the input's way to the system
                long lateness = Math.max(inputMargin, ticks.ceil(2 * clock.worstLatenessMicros()));
                Plan.Choice choice = plan.choose(elapsed, random, options.delayPolicy(),
                        options.delayBound() * ticksPerUnit, options.shortDelayBound() * ticksPerUnit,
                        input -> lateness + ticks.ceil(roomMicros(input.name())),
                        earliestInput(), steerer == null ? null : steerer.scorer());
                long at = reference.micros(choice.ticks());
                // a deadline within the test is declared missed only when the outputs stamped before it had the
                // reorder window to arrive
                boolean deadline = !choice.isInput() && choice.ticks() > plan.deadline() && deadlineBeforeTheEnd(plan);
                // an input the adapter holds until its time is performed ahead by the way it takes to the system
                long ahead = choice.isInput() ? leadMicros(choice.input().name(), at, now, ticks.micros(lateness)) : 0;
                long target = choice.isInput() ? at - ahead : deadline ? at + window() : Math.min(timeoutMicros, at);
                long wake = stopWake(now);
                if (wake < target) {
                    // a time(T) of the stop condition comes first: look at it then, and plan again
                    TestResult verdict = receive(clock.awaitUntil(wake));
                    if (verdict != null) {
                        return verdict;
                    }
                    continue;
                }
                announceWait(now, target, choice, plan);
                RunClock.TimedEvent event = clock.awaitUntil(target);
                if (event != null) {
                    TestResult verdict = receive(event);
                    if (verdict != null) {
                        return verdict;
                    }
                } else if (choice.isInput()) {
                    RunClock.TimedEvent earlier = clock.drain();
                    TestResult verdict = earlier != null ? receive(earlier)
                            : apply(choice, plan, ahead > 0 ? at : -1);
                    if (verdict != null) {
                        return verdict;
                    }
                } else if (deadline) {
                    if (clock.nowMicros() < at + window()) {
                        continue; // the window was widened while the tester waited
                    }
                    String deadlineAt = time(reference.micros(plan.deadline()));
                    java.util.Optional<String> unreachable = adapter.unreachable();
                    RunClock.TimedEvent meanwhile = clock.drain();
                    if (meanwhile != null) {
                        // came in while the adapter found out: judged first
                        TestResult verdict = receive(meanwhile);
                        if (verdict != null) {
                            return verdict;
                        }
                        continue;
                    }
                    if (choice.letsTimePass() && !plan.environmentLetsTimePass()) {
                        return result(Verdict.INCONCLUSIVE, "no input was applied by " + deadlineAt + ": the"
                                + " environment allowed inputs until then but no time to pass without one, and the"
                                + " tester let time pass " + whyTimePassed(choice) + ". " + plan.explainInputs(this::time,
                                reference.micros()));
                    }
                    if (plan.inputPossibleAt(plan.deadline()) && !choice.letsTimePass()) {
                        return result(Verdict.INCONCLUSIVE, "no input was applied by " + deadlineAt + ", when the"
                                + " environment's window closed: the tester learned of the events before it too late,"
                                + " or was held up (input executed too late). " + plan.explainInputs(this::time,
                                reference.micros()));
                    }
                    if (unreachable.isPresent()) {
                        return result(Verdict.INCONCLUSIVE, "no output came by " + deadlineAt + ", and the system"
                                + " under test may not have been able to act: " + unreachable.get());
                    }
                    return result(Verdict.FAILED, afterLastTaken() + "no output came by " + deadlineAt + ": the model required the"
                            + " system under test to act by then" + (window() > 0
                            ? " (the tester waited " + Plan.units(window(), unit) + " time units more for messages"
                            + " in transit)" : "") + (choice.letsTimePass() ? "; the environment allowed more inputs"
                            + " until then and lets time pass without them, and the tester let time pass "
                            + whyTimePassed(choice) : "") + ". " + plan.explainOutputs(this::time, reference.micros()));
                }
            }
        }

        /**
         * How far ahead of its time {@code at} an input on {@code channel} is performed: the adapter's lead ({@link
         * Adapter#inputLeadMicros}) and the tester's own {@code latenessMicros} in waking up, at most up to {@code
         * now}; 0 when the adapter holds no inputs (its lead is 0) or the run has no reorder window, which alone lets
         * the tester place an output that comes before an input it performed ahead.
         */
        private long leadMicros(String channel, long at, long now, long latenessMicros) {
            long lead = window() > 0 ? adapter.inputLeadMicros(channel) : 0;
            return lead <= 0 ? 0 : Math.max(0, Math.min(at - now, lead + latenessMicros));
        }

        /**
         * The room an input on {@code channel} needs before its window's end for its way to the system: the adapter's
         * {@link Adapter#inputDelayMicros}, and its lead as well when inputs are not sent ahead ({@link #leadMicros}).
         */
        private long roomMicros(String channel) {
            long room = Math.max(0, adapter.inputDelayMicros(channel));
            return window() == 0 ? room + Math.max(0, adapter.inputLeadMicros(channel)) : room;
        }

        /** The steerer's verdict on the goals at {@code now} (reached, or no longer reachable), or null. */
        private TestResult steered(long now) {
            if (steerer == null) {
                return null;
            }
            StateSet at = steerer.goalsDependOnTime() && now > lastMicros ? afterDelay(now, 0) : set;
            io.dtron.engine.internal.tester.Steerer.Stop stop = steerer.check(at, now, lastTaken != null
                    ? "after " + lastTaken + "," : "at " + time(lastMicros) + ",");
            return stop == null ? null : result(stop.verdict(), stop.explanation());
        }

        /** The run so far, as the stop condition reads it. */
        private StopCondition.Context stopContext(long now) {
            return new StopCondition.Context() {
                @Override
                public RunCoverage coverage() {
                    return coverage;
                }

                @Override
                public Goals goals() {
                    return goals;
                }

                @Override
                public double time() {
                    return (double) now / unit;
                }

                @Override
                public int inputs() {
                    return inputs;
                }
            };
        }

        /** When the stop condition's next {@code time(T)} after {@code now} comes, in microseconds, or never. */
        private long stopWake(long now) {
            if (until == null || stoppedBy != null) {
                return Long.MAX_VALUE;
            }
            long units = until.nextTime((double) now / unit);
            return units == Long.MAX_VALUE || !TestOptions.fits(units, unit) ? Long.MAX_VALUE : units * unit;
        }

        /** Records the step of a committed event in the coverage, and tells the listeners. */
        private void record(Pending p) {
            if (p.taken == null) {
                return;
            }
            coverage.commit(p.taken, p.event, p.input, p.after);
            if (!listeners.isEmpty()) {
                List<String> certainly = coverage.describe(p.taken.certainly());
                List<String> possibly = coverage.describe(p.taken.possibly());
                for (TestListener l : listeners) {
                    l.edgesTaken(p.event, p.input, p.micros, certainly, possibly);
                }
            }
            p.taken = null;
        }

        /** At the end: records the events judged allowed that the tester had not committed to yet. */
        void recordPending() {
            for (Pending p : pending) {
                record(p);
            }
        }

        /**
         * The earliest tick (after the last event) of the next input: 0, or, after {@link #MAX_INPUTS_AT_ONE_INSTANT}
         * inputs at one instant, one time unit after that instant.
         */
        private long earliestInput() {
            if (inputsAtInstant < MAX_INPUTS_AT_ONE_INSTANT) {
                return 0;
            }
            return Math.max(1, reference.ceil(instantMicros + unit));
        }

        /** Why the tester let time pass while the environment allowed an input, for explanations. */
        private String whyTimePassed(Plan.Choice choice) {
            if (choice.steered()) {
                return "for the system to act, as the strategy chose (waiting for it scored best)";
            }
            return inputsAtInstant >= MAX_INPUTS_AT_ONE_INSTANT ? "after " + inputsAtInstant + " inputs at "
                    + time(instantMicros) + " (it gives at most " + MAX_INPUTS_AT_ONE_INSTANT + " inputs at one instant)"
                    : "rather than aim an input less than its input margin before the deadline";
        }

        /** Counts an input applied at {@code micros} towards the inputs at one instant. */
        private void countInstant(long micros) {
            long instant = options.virtualTime() ? 0 : options.inputMarginMicros();
            if (instantMicros >= 0 && micros - instantMicros <= instant) {
                inputsAtInstant++;
            } else {
                instantMicros = micros;
                inputsAtInstant = 1;
            }
        }

        private void announceWait(long now, long target, Plan.Choice choice, Plan plan) {
            if (listeners.isEmpty()) {
                return;
            }
            TestListener.Until until = choice.isInput() ? TestListener.Until.INPUT
                    : plan.hasDeadline() ? TestListener.Until.OUTPUT_DEADLINE : TestListener.Until.END;
            long untilMicros = until == TestListener.Until.OUTPUT_DEADLINE ? reference.micros(plan.deadline())
                    : target;
            for (TestListener l : listeners) {
                l.waiting(now, untilMicros, until);
            }
        }
        /**
         * A pending input sent at or before {@code at} whose acknowledgement has not come, when the adapter
         * acknowledges inputs (it says so, or some acknowledgement came in this run); else null.
         */
        private Pending awaitingAcknowledgement(long at) {
            if (!expectsAcknowledgements()) {
                return null;
            }
            for (Pending p : pending) {
                if (p.input && !p.acknowledged && p.sentMicros <= at) {
                    return p;
                }
            }
            return null;
        }

        /**
         * Until when, from {@code micros}, an acknowledgement is waited for before what follows its input is committed
         * to, or a verdict that depends on where it was applied is given: {@link #ACK_PATIENCE} reorder windows; without
         * a reorder window (an adapter in the tester's process, in virtual time above all, that applies an input later
         * than it was performed) until the end of the run, so that an output that came between the two is judged
         * before the input, as it happened.
         */
        private long ackDeadline(long micros) {
            return window() > 0 ? micros + ACK_PATIENCE * window() : Math.max(micros, timeoutMicros);
        }

        /** Whether inputs are acknowledged: the adapter says so, or some acknowledgement came in this run. */
        private boolean expectsAcknowledgements() {
            return acknowledgements > 0 || adapter.acknowledgesInputs();
        }

        /**
         * Commits to the pending events at or before {@code horizon}: nothing earlier can arrive any more. An input
         * whose acknowledgement is still expected (for up to {@link #ACK_PATIENCE} reorder windows after it was
         * sent) is not committed yet, nor what follows it.
         */
        private void commit(long horizon) {
            while (!pending.isEmpty() && pending.get(0).micros <= horizon) {
                Pending first = pending.get(0);
                if (first.input && !first.acknowledged && expectsAcknowledgements()
                        && horizon < ackDeadline(first.sentMicros)) {
                    break; // where it was applied is still to come, and so is the order of what follows it
                }
                Pending p = pending.remove(0);
                record(p);
                committed = p.after;
                committedMicros = p.afterMicros;
                committedReference = p.afterReference;
                if (p.input) {
                    committedInputs.put(p.ordinal, p);
                    if (p.doubtful) {
                        doubtCommitted = p;
                    }
                }
            }
            committedInputs.values().removeIf(p -> p.sentMicros < horizon - window());
        }

        /** Takes what an adapter reported; returns a verdict that ends the run, or null. */
        private TestResult receive(RunClock.TimedEvent timed) {
            if (timed == null) {
                return null;
            }
            if (timed.abort() != null) {
                return result(Verdict.INCONCLUSIVE, timed.abort() + " (at " + time(timed.micros()) + ")");
            }
            if (timed.appliedInput() > 0) {
                return acknowledged(timed.appliedInput(), timed.micros(), timed.uncertainty());
            }
            Event event = timed.event();
            long at = timed.micros();
            long now = clock.nowMicros();
            if (held == null) {
                commit(now - window());
            }
            if (window() == 0) {
                // a scheduled task that ran late reports at its due time, which may be before the last event seen:
                // the tester has committed to that event, so the output comes after it
                at = Math.max(at, lastMicros);
            } else if (at < committedMicros) {
                return result(Verdict.INCONCLUSIVE, "output " + event + " happened at " + time(at) + " but reached"
                        + " the tester at " + time(now) + ", " + Plan.units(now - at, unit) + " time units later:"
                        + " more than the reorder window of " + Plan.units(window(), unit) + " time units, after the"
                        + " tester had committed to events up to " + time(committedMicros) + "; its place among them"
                        + " is unknown");
            }
            if (at > timeoutMicros) {
                return null; // after the end of the test
            }
            TestInterface.ObservableChannel channel = testInterface.output(event.channel()).orElse(null);
            if (channel == null) {
                return result(Verdict.INCONCLUSIVE, "the adapter reported '" + event.channel() + "' at " + time(at)
                        + ", which is not an output of the model's interface");
            }
            String badValues = checkNames(channel, event);
            if (badValues != null) {
                return result(Verdict.INCONCLUSIVE, "the adapter reported " + event + " at " + time(at) + ": "
                        + badValues);
            }
            if (!listeners.isEmpty()) {
                announceWindow(event, channel, at);
            }
            for (TestListener l : listeners) {
                l.outputObserved(event, at);
            }
            outputs++;
            Pending output = new Pending(event, false, 0, at);
            output.uncertainty = timed.uncertainty();
            return place(output);
        }

        /** Input number {@code ordinal} was applied at {@code micros}: places it there. */
        private TestResult acknowledged(long ordinal, long micros, long uncertainty) {
            if (held == null) {
                commit(clock.nowMicros() - window());
            }
            for (Pending p : pending) {
                if (p.input && p.ordinal == ordinal) {
                    acknowledgements++;
                    p.acknowledged = true;
                    pending.remove(p);
                    // an input is not applied before it is sent: an earlier time is the clocks' error
                    p.micros = Math.max(micros, p.sentMicros);
                    p.uncertainty = uncertainty;
                    return place(p);
                }
            }
            Pending input = committedInputs.remove(ordinal);
            if (input != null) {
                acknowledgements++;
            }
            if (input != null && micros - input.sentMicros > window()) {
                return result(Verdict.INCONCLUSIVE, "input " + input.event + ", " + input.sentOrDue() + " at "
                        + time(input.sentMicros)
                        + ", was applied at " + time(micros) + ", " + Plan.units(micros - input.sentMicros, unit)
                        + " time units later: more than the reorder window of " + Plan.units(window(), unit) + " time"
                        + " units, after the tester had committed to it");
            }
            return null;
        }

        /**
         * Puts an event among the pending ones by its time and judges the events from there on. A verdict is held
         * until no event before the one it concerns can arrive any more; without a reorder window it is final, but for
         * one that waits for the acknowledgement of an input sent before the event it concerns ({@link #ackDeadline}).
         */
        private TestResult place(Pending event) {
            int index = pending.size();
            while (index > 0 && pending.get(index - 1).micros > event.micros) {
                index--;
            }
            pending.add(index, event);
            int from = held == null ? index : 0;
            if (from == 0) {
                set = committed;
                lastMicros = committedMicros;
                reference = committedReference;
            } else {
                set = pending.get(from - 1).after;
                lastMicros = pending.get(from - 1).afterMicros;
                reference = pending.get(from - 1).afterReference;
            }
            held = null;
            for (int i = from; i < pending.size(); i++) {
                pending.get(i).taken = null;
            }
            for (int i = from; i < pending.size(); i++) {
                Pending p = pending.get(i);
                TestResult verdict = p.input ? reapply(p) : judge(p.event, p.micros, p.uncertainty);
                if (verdict != null) {
                    if (window() == 0 && awaitingAcknowledgement(p.micros) == null) {
                        return verdict;
                    }
                    held = new Held(verdict, p.micros + window(), p.micros);
                    return null;
                }
                p.after = set;
                p.afterMicros = lastMicros;
                p.afterReference = reference;
                p.taken = lastStep;
            }
            return null;
        }

        /**
         * Judges output {@code event} at {@code at}, give or take {@code uncertainty}, on the state set: a verdict, or
         * null when it is allowed.
         */
        private TestResult judge(Event event, long at, long uncertainty) {
            TestInterface.ObservableChannel channel = testInterface.output(event.channel()).orElseThrow();
            StateSet atTime = afterDelay(at, uncertainty);
            if (atTime.isEmpty()) {
                Pending late = inputAppliedAfter(at);
                if (late != null) {
                    return result(Verdict.INCONCLUSIVE, "input " + late.event + ", " + late.sentOrDue() + " at "
                            + time(late.sentMicros)
                            + ", was applied at " + time(late.micros) + ", after output " + event + " happened at "
                            + time(at) + ": the model cannot let that much time pass before the input (input"
                            + " executed too late)");
                }
                TestResult missed = missedInput(event, at, uncertainty);
                if (missed != null) {
                    return missed;
                }
                TestResult doubt = doubtfulInput(event, at);
                if (doubt != null) {
                    return doubt;
                }
                return result(Verdict.FAILED, afterLastTaken() + "output " + event + " observed at " + time(at)
                        + " is too late: "
                        + plan().explainOutputs(this::time, reference.micros()));
            }
            List<StateSet.Successor> moves = atTime.successors(channel.channel());
            List<io.dtron.engine.internal.sem.SymState> matching = new ArrayList<>();
            List<StateSet.Successor> taken = new ArrayList<>();
            for (StateSet.Successor s : moves) {
                if (valuesMatch(channel, event, s.state())) {
                    matching.add(s.state());
                    taken.add(s);
                }
            }
            if (!matching.isEmpty() && steerer != null) {
                io.dtron.engine.internal.tester.Steerer.Stop stop = steerer.taken(taken, at, inputs, true);
                if (stop != null) {
                    return result(stop.verdict(), stop.explanation());
                }
            }
            if (!matching.isEmpty()) {
                lastStep = coverage.step(set.states(), taken);
                set = atTime.of(matching);
                lastMicros = at;
                reference = reference.plus(reference.windowStart(at - uncertainty));
                lastTaken = "output " + event + " at " + time(at) + " was taken as " + edgesTaken(channel, event, moves);
                return null;
            }
            if (!moves.isEmpty()) {
                TestResult doubt = doubtfulInput(event, at);
                if (doubt != null) {
                    return doubt;
                }
                return result(Verdict.FAILED, afterLastTaken() + "output " + event + " observed at " + time(at)
                        + " carries values the"
                        + " model does not allow then: it allowed " + allowedValues(channel, moves) + " ("
                        + semantics.describe(moves.get(0).move().steps().get(0)) + ")");
            }
            String envRefusal = Plan.environmentRefuses(atTime, semantics, partition, channel.channel());
            if (envRefusal != null) {
                return result(Verdict.INCONCLUSIVE, "the environment model cannot accept output " + event + " at "
                        + time(at) + ": " + envRefusal);
            }
            TestResult missed = missedInput(event, at, uncertainty);
            if (missed != null) {
                return missed;
            }
            TestResult doubt = doubtfulInput(event, at);
            if (doubt != null) {
                return doubt;
            }
            Plan plan = plan();
            return result(Verdict.FAILED, afterLastTaken() + "output " + event + " observed at " + time(at)
                    + " is not allowed then"
                    + plan.timing(channel.channel(), reference.floor(at)) + ". "
                    + plan.explainOutputs(this::time, reference.micros()));
        }

        /**
         * INCONCLUSIVE when output {@code event} at {@code at}, give or take {@code uncertainty}, may have come after
         * the deadline by which the tester was to apply an input (one was possible then, so it does not wait past it)
         * and it applied none: the output cannot be judged after an input the tester missed (it was held up, or the
         * output's stamp ran ahead of its clock). Else null.
         */
        private TestResult missedInput(Event event, long at, long uncertainty) {
            Plan plan = plan();
            long deadline = reference.micros(plan.deadline());
            if (!plan.hasDeadline() || at + uncertainty <= deadline || !plan.inputPossibleAt(plan.deadline())) {
                return null;
            }
            return result(Verdict.INCONCLUSIVE, "output " + event + " observed at " + time(at) + (uncertainty > 0
                    ? " (give or take " + Plan.units(uncertainty, unit) + " time units)" : "") + " may have come after "
                    + time(deadline) + ", when the environment's window for an input closed, and the tester had"
                    + " applied none by then (input executed too late). " + plan.explainInputs(this::time,
                    reference.micros()));
        }

        /**
         * INCONCLUSIVE when an input before output {@code event} at {@code at} was allowed only within its clock error
         * of where its adapter applied it ({@link Pending#doubtful}): the model was followed as if it came in time,
         * but it may have come after the environment's window closed, and the output that contradicts the model then
         * may be its consequence. Else null.
         */
        private TestResult doubtfulInput(Event event, long at) {
            Pending doubt = doubtCommitted;
            for (Pending p : pending) {
                if (p.input && p.doubtful && p.micros <= at) {
                    doubt = p;
                }
            }
            if (doubt == null) {
                return null;
            }
            return result(Verdict.INCONCLUSIVE, "output " + event + " observed at " + time(at) + " is not what the"
                    + " model allows after input " + doubt.event + ", which was applied at " + time(doubt.micros)
                    + " give or take " + Plan.units(doubt.uncertainty, unit) + " time units: the environment allowed"
                    + " it only within that clock error, so it may have come after its window closed (input executed"
                    + " too late)");
        }

        /**
         * The state set at {@code at}, give or take {@code uncertainty} microseconds (but not before the set's time):
         * every state the model can be in at some time of that interval, each keeping when in it (the set's time is
         * then the window's start after {@link #reference}).
         */
        private StateSet afterDelay(long at, long uncertainty) {
            coverage.begin();
            return set.within(reference.windowStart(at - uncertainty), reference.ceil(at + uncertainty),
                    coverage.internalMoves());
        }

        /** The distinct edges of {@code moves} whose values match {@code event}, for explanations. */
        private String edgesTaken(TestInterface.ObservableChannel channel, Event event, List<StateSet.Successor> moves) {
            java.util.Set<String> edges = new java.util.LinkedHashSet<>();
            for (StateSet.Successor s : moves) {
                if (valuesMatch(channel, event, s.state())) {
                    edges.add(semantics.describe(s.move().steps().get(0)));
                }
            }
            return String.join(" or ", edges);
        }

        /**
         * "OUTPUT at t=... was taken as EDGE; then " when the last observation moved the state set, so that a verdict
         * that follows it says which way the tester understood it; "" otherwise.
         */
        private String afterLastTaken() {
            return lastTaken == null ? "" : lastTaken + "; then ";
        }

        /** A pending input sent at or before {@code at} but applied after it, or null. */
        private Pending inputAppliedAfter(long at) {
            for (Pending p : pending) {
                if (p.input && p.sentMicros <= at && p.micros > at) {
                    return p;
                }
            }
            return null;
        }

        /** Applies pending input {@code p} again, with its values, at its (possibly new) time. */
        private TestResult reapply(Pending p) {
            TestInterface.ObservableChannel channel = testInterface.input(p.event.channel()).orElseThrow();
            StateSet atTime = afterDelay(p.micros, p.uncertainty);
            List<io.dtron.engine.internal.sem.SymState> next = new ArrayList<>();
            List<StateSet.Successor> taken = new ArrayList<>();
            for (StateSet.Successor s : atTime.successors(channel.channel())) {
                if (valuesOf(channel, s.state()).equals(p.event.values())) {
                    next.add(s.state());
                    taken.add(s);
                }
            }
            if (next.isEmpty()) {
                String late = p.micros > p.sentMicros ? " It was " + p.sentOrDue() + " at " + time(p.sentMicros)
                        + " and applied "
                        + Plan.units(p.micros - p.sentMicros, unit) + " time units later." : "";
                return result(Verdict.INCONCLUSIVE, "input " + p.event + " was executed at " + time(p.micros)
                        + ", when the environment no longer allowed it, after the events that happened before it"
                        + " (input executed too late)." + late + " "
                        + plan().explainInputs(this::time, reference.micros()));
            }
            // allowed within the clocks' error of where it was applied, but not there: it may have come too late
            p.doubtful = p.uncertainty > 0;
            for (StateSet.Successor s : p.doubtful ? afterDelay(p.micros, 0).successors(channel.channel())
                    : List.<StateSet.Successor>of()) {
                p.doubtful &= !valuesOf(channel, s.state()).equals(p.event.values());
            }
            lastStep = coverage.step(set.states(), taken);
            set = atTime.of(next);
            lastMicros = p.micros;
            reference = reference.plus(reference.windowStart(p.micros - p.uncertainty));
            return null;
        }

        /**
         * Applies the chosen input now, or, when {@code dueMicros} is not negative, performs it now for that later
         * time ({@link Adapter#perform(Event, long)}) and places it there.
         */
        private TestResult apply(Plan.Choice choice, Plan plan, long dueMicros) {
            long quiet = clock.quietNow();
            if (quiet < 0) {
                return null; // an output came in after the drain: the loop observes it, then plans again
            }
            boolean ahead = dueMicros > quiet;
            long now = ahead ? dueMicros : quiet;
            TestInterface.ObservableChannel channel = choice.input();
            StateSet atTime = afterDelay(now, 0);
            List<StateSet.Successor> moves = atTime.successors(channel.channel());
            if (moves.isEmpty()) {
                return result(Verdict.INCONCLUSIVE, "input " + channel.name() + " could not be applied at "
                        + time(now) + " (too late for the window the environment allowed). "
                        + plan.explainInputs(this::time, reference.micros()));
            }
            StateSet.Successor chosen = moves.get(random.nextInt(moves.size()));
            Map<String, Integer> values = valuesOf(channel, chosen.state());
            Event event = new Event(channel.name(), values);
            // published first, the bookkeeping after: the input's way to the system starts at its time
            try {
                if (ahead) {
                    adapter.perform(event, now);
                } else {
                    adapter.perform(event);
                }
            } catch (RuntimeException | AssertionError e) {
                return result(Verdict.INCONCLUSIVE, RunClock.thrown("the system under test", e) + " when input "
                        + event + " was applied at " + time(now));
            }
            List<io.dtron.engine.internal.sem.SymState> next = new ArrayList<>();
            List<StateSet.Successor> taken = new ArrayList<>();
            for (StateSet.Successor s : moves) {
                if (valuesOf(channel, s.state()).equals(values)) {
                    next.add(s.state());
                    taken.add(s);
                }
            }
            if (steerer != null) {
                steerer.taken(taken, now, inputs + 1, false);
            }
            Recorder.Step step = coverage.step(set.states(), taken);
            set = atTime.of(next);
            lastMicros = now;
            reference = reference.plus(reference.windowStart(now));
            lastTaken = null;
            Pending p = new Pending(event, true, ++performed, now);
            p.ahead = ahead;
            p.after = set;
            p.afterMicros = now;
            p.afterReference = reference;
            p.taken = step;
            pending.add(p);
            inputs++;
            countInstant(now);
            for (TestListener l : listeners) {
                l.inputApplied(event, now);
            }
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

        private String time(long micros) {
            return ticks.time(micros);
        }
    }
}
