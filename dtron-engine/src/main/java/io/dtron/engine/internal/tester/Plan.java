package io.dtron.engine.internal.tester;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.internal.sem.DiscreteCache;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Random;
import java.util.function.LongFunction;
import java.util.function.ToLongFunction;

/**
 * What may happen next, seen from the last observation: for every observable channel the windows of elapsed
 * time (in ticks) in which the model allows it, and the deadline by which something must happen. The tester
 * chooses its next input from this and explains its verdicts with it.
 */
public final class Plan {
    private final Semantics semantics;
    private final long unitMicros;
    private final long horizon;
    private final long deadline;
    private final Map<Integer, List<Window>> windows;
    private final Map<Integer, TestInterface.ObservableChannel> inputs;
    private final Map<Integer, String> names;
    private final String implementationState;
    /** The states reachable before the horizon, and the partition, for {@link #environmentLetsTimePass}. */
    private final List<SymState> reach;
    private final Partition partition;
    private Boolean environmentLetsTimePass;

    /**
     * A window of elapsed ticks in which a channel is enabled, with the edge that would take it, the state it is
     * taken from and the move.
     */
    record Window(long lo, long hi, Semantics.Step edge, SymState from, Semantics.Move move) {
    }

    /**
     * Scores the tester's moves for a steering strategy: the fewer moves from where one leads to the strategy's
     * nearest target, the better; {@link io.dtron.engine.internal.verify.DiscreteGraph#UNREACHABLE} when it does not
     * steer.
     */
    public interface Scorer {
        /** The score of the input {@code move} from {@code from}. */
        int input(SymState from, Semantics.Move move);

        /** The score of waiting for the system in the states {@code reach}. */
        int waiting(List<SymState> reach);

        /**
         * How long after the last event, in ticks, waiting for the system is worth it in the states {@code reach}:
         * past the largest clock constant that matters there, time alone changes nothing.
         */
        long patience(List<SymState> reach);
    }

    /**
     * The tester's next move: an input after {@code ticks}, or (input null) waiting until {@code ticks}; {@code
     * letsTimePass} when the tester waits past a deadline at which the environment allowed an input (it lets time
     * pass rather than give more inputs at one instant, or an input it could not aim a margin before the deadline, or
     * because a strategy waits for the system); {@code steered} when a strategy chose it.
     */
    public record Choice(TestInterface.ObservableChannel input, long ticks, boolean letsTimePass, boolean steered) {
        /** A choice that no strategy steered. */
        public Choice(TestInterface.ObservableChannel input, long ticks, boolean letsTimePass) {
            this(input, ticks, letsTimePass, false);
        }

        /** Whether this applies an input. */
        public boolean isInput() {
            return input != null;
        }
    }

    private Plan(Semantics semantics, long unitMicros, long horizon, long deadline,
                 Map<Integer, List<Window>> windows, Map<Integer, TestInterface.ObservableChannel> inputs,
                 Map<Integer, String> names, String implementationState, List<SymState> reach, Partition partition) {
        this.semantics = semantics;
        this.unitMicros = unitMicros;
        this.horizon = horizon;
        this.deadline = deadline;
        this.windows = windows;
        this.inputs = inputs;
        this.names = names;
        this.implementationState = implementationState;
        this.reach = reach;
        this.partition = partition;
    }

    /** The plan for {@code set}, looking at most {@code horizon} ticks ahead; {@code unitMicros} per time unit. */
    public static Plan of(StateSet set, Semantics semantics, Partition partition, TestInterface testInterface,
                          long unitMicros, long horizon) {
        int elapsed = semantics.elapsedClock();
        Map<Integer, TestInterface.ObservableChannel> inputs = new LinkedHashMap<>();
        Map<Integer, String> names = new LinkedHashMap<>();
        for (TestInterface.ObservableChannel c : testInterface.inputs()) {
            inputs.put(c.channel(), c);
            names.put(c.channel(), c.name());
        }
        for (TestInterface.ObservableChannel c : testInterface.outputs()) {
            names.put(c.channel(), c.name());
        }
        // per channel, in the order channels are first seen
        List<List<Window>> byChannel = new ArrayList<>(Collections.nCopies(semantics.network().channelCount(), null));
        List<Integer> seen = new ArrayList<>();
        long deadline = 0;
        List<SymState> reach = set.reach(horizon);
        DiscreteCache cache = set.observableMoves();
        for (SymState s : reach) {
            deadline = Math.max(deadline, upper(s, elapsed, horizon));
            cache.clockBounds(s, elapsed, (move, upper, lowerNeg) -> {
                List<Window> ws = byChannel.get(move.channel());
                if (ws == null) {
                    ws = new ArrayList<>();
                    byChannel.set(move.channel(), ws);
                    seen.add(move.channel());
                }
                ws.add(new Window(lower(lowerNeg), upper(upper, horizon), move.steps().get(0), s, move));
            });
        }
        Map<Integer, List<Window>> windows = new LinkedHashMap<>();
        for (int channel : seen) {
            windows.put(channel, byChannel.get(channel));
        }
        boolean[] implementation = new boolean[semantics.network().processes().size()];
        for (int p = 0; p < implementation.length; p++) {
            implementation[p] = !partition.isEnvironment(p);
        }
        String state = set.states().isEmpty() ? "" : semantics.describe(set.states().get(0), implementation);
        return new Plan(semantics, unitMicros, horizon, Math.min(deadline, horizon), windows, inputs, names, state,
                reach, partition);
    }

    private static long upper(SymState s, int clock, long horizon) {
        return upper(s.zone().upperBound(clock), horizon);
    }

    /** The earliest tick of a clock whose negation has the raw bound {@code lowerNeg}. */
    private static long lower(int lowerNeg) {
        if (Bound.isInfinite(lowerNeg)) {
            return 0;
        }
        long v = -Bound.value(lowerNeg);
        return Bound.isStrict(lowerNeg) ? v + 1 : v;
    }

    /** The latest tick (at most {@code horizon}) of a clock with the raw upper bound {@code raw}. */
    private static long upper(int raw, long horizon) {
        if (Bound.isInfinite(raw)) {
            return horizon;
        }
        long v = Bound.value(raw);
        return Math.min(horizon, Bound.isStrict(raw) ? v - 1 : v);
    }

    /** The windows (merged) in which channel number {@code channel} is allowed. */
    List<Window> windowsOf(int channel) {
        return merge(windows.getOrDefault(channel, List.of()));
    }

    /**
     * The window of elapsed ticks, {@code [lo, hi]}, in which channel number {@code channel} is allowed that holds
     * {@code atTicks}, else the next one after it, else the last one before it; {@code hi} is {@link Long#MAX_VALUE}
     * when the window stays open to the horizon. Null when the channel is not allowed at all before the horizon.
     */
    public long[] windowAt(int channel, long atTicks) {
        List<Window> ws = windowsOf(channel);
        if (ws.isEmpty()) {
            return null;
        }
        Window pick = ws.get(ws.size() - 1);
        for (Window w : ws) {
            if (atTicks <= w.hi()) {
                pick = w;
                break;
            }
        }
        return new long[] {pick.lo(), pick.hi() >= horizon ? Long.MAX_VALUE : pick.hi()};
    }

    /** Whether something must happen before the horizon. */
    public boolean hasDeadline() {
        return deadline < horizon;
    }

    /**
     * Whether the environment may apply an input at {@code ticks}: then a deadline there can be met by the tester,
     * and a tester that missed it (it learned of the events before too late, or was held up) is at fault, not the
     * system under test.
     */
    public boolean inputPossibleAt(long ticks) {
        for (Map.Entry<Integer, List<Window>> e : windows.entrySet()) {
            if (inputs.containsKey(e.getKey())) {
                for (Window w : e.getValue()) {
                    if (w.lo() <= ticks && ticks <= w.hi()) {
                        return true;
                    }
                }
            }
        }
        return false;
    }

    /** The elapsed ticks by which something must happen (the horizon when nothing must). */
    public long deadline() {
        return deadline;
    }

    /**
     * Whether the environment, on its own, lets time pass beyond the deadline: in every state that is possible at
     * the deadline no environment process is urgent or committed and their invariants allow more time. Then the
     * deadline is the implementation's: if the tester lets time pass, the system under test must act by it. True
     * when nothing must happen before the horizon.
     */
    public boolean environmentLetsTimePass() {
        if (environmentLetsTimePass == null) {
            boolean lets = true;
            if (hasDeadline()) {
                int clock = semantics.elapsedClock();
                for (SymState s : reach) {
                    if (upper(s, clock, horizon) >= deadline
                            && !semantics.mayDelayPast(s, partition::isEnvironment, clock, deadline)) {
                        lets = false;
                        break;
                    }
                }
            }
            environmentLetsTimePass = lets;
        }
        return environmentLetsTimePass;
    }

    /**
     * {@link #choose(long, Random, DelayPolicy, long, long, ToLongFunction, long) Chooses} with no short bound and no
     * earliest input.
     */
    public Choice choose(long elapsed, Random random, DelayPolicy policy, long boundTicks,
                         ToLongFunction<TestInterface.ObservableChannel> marginTicks) {
        return choose(elapsed, random, policy, boundTicks, 0, marginTicks, 0);
    }

    /**
     * Chooses the next move at {@code elapsed} ticks: an input among those the environment allows (with its
     * time by {@code policy}), or waiting until the deadline (or the horizon). When an input is possible at the
     * deadline, the tester does not wait past it, with two exceptions, where it lets time pass (the choice {@link
     * Choice#letsTimePass}): no input earlier than {@code earliestTicks} (the tester has given as many inputs at one
     * instant as it gives, and time must advance), and, when the environment lets time pass beyond the deadline
     * ({@link #environmentLetsTimePass}), no input in a window that ends at the deadline less than the {@code
     * marginTicks} of its channel after it opens (the tester could not meet it reliably; the system under test must
     * act by the deadline anyway). An input's time is chosen at least the {@code marginTicks} of its channel before
     * the end of its window (at the window's start when it is narrower than that), so that an input sent by a tester
     * that wakes up a little late, and that takes a while to reach the system, still lands inside the window: as late
     * as can still be met, for {@link DelayPolicy#LAZY}. For {@link DelayPolicy#RANDOM_BOUNDED} the bound is {@code
     * boundTicks}, or, when {@code shortBoundTicks} is positive, {@code shortBoundTicks} or {@code boundTicks} at
     * random (TRON's {@code -P SHORT,LONG}).
     */
    public Choice choose(long elapsed, Random random, DelayPolicy policy, long boundTicks, long shortBoundTicks,
                         ToLongFunction<TestInterface.ObservableChannel> marginTicks, long earliestTicks) {
        return choose(elapsed, random, policy, boundTicks, shortBoundTicks, marginTicks, earliestTicks, null);
    }

    /**
     * {@link #choose(long, Random, DelayPolicy, long, long, ToLongFunction, long) Chooses}, steered by {@code
     * scorer} when it is not null: among the inputs with the best score (at random between equals), at the start of
     * its window; waiting when that scores at least as well as every input (the system moves on by itself): until
     * the deadline (past a window for an input only when the environment lets time pass there, so that the deadline
     * is the system's), else the best input as late as its window allows; without a deadline, until time alone
     * changes nothing ({@link Scorer#patience}). When nothing scores within the horizon,
     * the choice is the unsteered one.
     */
    public Choice choose(long elapsed, Random random, DelayPolicy policy, long boundTicks, long shortBoundTicks,
                         ToLongFunction<TestInterface.ObservableChannel> marginTicks, long earliestTicks,
                         Scorer scorer) {
        List<long[]> options = new ArrayList<>();
        List<Window> origins = new ArrayList<>();
        List<TestInterface.ObservableChannel> channels = new ArrayList<>();
        boolean mustAct = false;
        boolean couldActAtDeadline = false;
        for (Map.Entry<Integer, List<Window>> e : windows.entrySet()) {
            TestInterface.ObservableChannel input = inputs.get(e.getKey());
            if (input == null) {
                continue;
            }
            long margin = marginTicks.applyAsLong(input);
            for (Window w : e.getValue()) {
                long lo = Math.max(w.lo(), elapsed);
                long hi = hasDeadline() ? Math.min(w.hi(), deadline) : w.hi();
                couldActAtDeadline |= hasDeadline() && lo <= deadline && deadline <= w.hi();
                lo = Math.max(lo, earliestTicks);
                if (lo > hi || margin > 0 && hi - margin < lo && hasDeadline() && w.hi() >= deadline
                        && environmentLetsTimePass()) {
                    continue;
                }
                // never later than the margin before the end: the tester is never early, only late, so in a
                // window narrower than the margin the start gives it the most room
                options.add(new long[] {lo, Math.max(lo, hi - margin)});
                channels.add(input);
                origins.add(w);
                mustAct |= hasDeadline() && lo <= deadline && deadline <= w.hi();
            }
        }
        // waiting is a choice of its own only when something must happen by a deadline: otherwise an input's
        // random time already covers waiting, and the tester would wait to the end of the test
        boolean offerWait = options.isEmpty() || hasDeadline() && !mustAct;
        if (scorer != null && !options.isEmpty()) {
            Choice steered = steer(scorer, elapsed, options, channels, origins, random, mustAct,
                    couldActAtDeadline);
            if (steered != null) {
                return steered;
            }
        }
        int count = options.size() + (offerWait ? 1 : 0);
        int pick = options.isEmpty() ? 0 : random.nextInt(count);
        if (pick == options.size()) {
            // waiting past a deadline at which an input was possible, when the tester no longer offers it
            return new Choice(null, hasDeadline() ? deadline + 1 : horizon, couldActAtDeadline && !mustAct);
        }
        long lo = options.get(pick)[0];
        long hi = options.get(pick)[1];
        long ticks = switch (policy) {
            case EAGER -> lo;
            case LAZY -> hi;
            case RANDOM -> lo + (long) Math.floor(random.nextDouble() * (hi - lo + 1));
            case RANDOM_BOUNDED -> {
                long bound = shortBoundTicks > 0 && random.nextBoolean() ? shortBoundTicks : boundTicks;
                long top = Math.min(hi, lo + bound);
                yield lo + (long) Math.floor(random.nextDouble() * (top - lo + 1));
            }
        };
        return new Choice(channels.get(pick), Math.min(ticks, hi), false);
    }

    private Choice steer(Scorer scorer, long elapsed, List<long[]> options, List<TestInterface.ObservableChannel> channels,
                         List<Window> origins, Random random, boolean mustAct, boolean couldActAtDeadline) {
        int best = io.dtron.engine.internal.verify.DiscreteGraph.UNREACHABLE;
        List<Integer> bestOptions = new ArrayList<>();
        for (int i = 0; i < options.size(); i++) {
            int score = scorer.input(origins.get(i).from(), origins.get(i).move());
            if (score < best) {
                best = score;
                bestOptions.clear();
            }
            if (score == best) {
                bestOptions.add(i);
            }
        }
        // waiting for a system that need not act is worth it only until time alone changes nothing: then act
        long patience = hasDeadline() ? Long.MAX_VALUE : scorer.patience(reach);
        int wait = elapsed >= patience ? io.dtron.engine.internal.verify.DiscreteGraph.UNREACHABLE
                : scorer.waiting(reach);
        if (wait >= io.dtron.engine.internal.verify.DiscreteGraph.UNREACHABLE
                && best >= io.dtron.engine.internal.verify.DiscreteGraph.UNREACHABLE) {
            return null;
        }
        if (wait <= best) {
            if (!mustAct) {
                return new Choice(null, hasDeadline() ? deadline + 1 : Math.min(horizon, patience),
                        couldActAtDeadline, true);
            }
            if (environmentLetsTimePass()) {
                // the deadline is the system's: it must act by then whatever the environment does, so the tester
                // may wait for it past a window in which it could have given an input
                return new Choice(null, deadline + 1, true, true);
            }
            // an input must come by the deadline: the best one, as late as it can, to give the system its time
            int pick = bestOptions.isEmpty() ? random.nextInt(options.size())
                    : bestOptions.get(random.nextInt(bestOptions.size()));
            return new Choice(channels.get(pick), options.get(pick)[1], false);
        }
        int pick = bestOptions.get(random.nextInt(bestOptions.size()));
        return new Choice(channels.get(pick), options.get(pick)[0], false);
    }

    /** The outputs the model allowed, with their times, and the implementation's state, for explanations. */
    public String explainOutputs(LongFunction<String> time, long baseMicros) {
        return explain(time, baseMicros, false);
    }

    /** The inputs the environment allowed, with their times. */
    public String explainInputs(LongFunction<String> time, long baseMicros) {
        return explain(time, baseMicros, true);
    }

    private String explain(LongFunction<String> time, long baseMicros, boolean wantInputs) {
        StringBuilder sb = new StringBuilder();
        for (Map.Entry<Integer, List<Window>> e : windows.entrySet()) {
            if (inputs.containsKey(e.getKey()) != wantInputs) {
                continue;
            }
            for (Window w : merge(e.getValue())) {
                sb.append(sb.length() == 0 ? "" : "; ").append(names.get(e.getKey())).append(" between ")
                        .append(time.apply(baseMicros + micros(w.lo()))).append(" and ")
                        .append(w.hi() >= horizon ? "the end of the test" : time.apply(baseMicros + micros(w.hi())))
                        .append(" (").append(semantics.describe(w.edge())).append(')');
            }
        }
        String what = wantInputs ? "inputs" : "outputs";
        String allowed = sb.length() == 0 ? "The model allowed no " + what + " then"
                : "The model allowed these " + what + ": " + sb;
        return allowed + (wantInputs || implementationState.isEmpty() ? ""
                : ". At the last observation the implementation was in " + implementationState) + ".";
    }

    /** " (too early: ...)" or " (too late: ...)" when {@code channel} is allowed at other times, else "". */
    public String timing(int channel, long atTicks) {
        List<Window> ws = windows.get(channel);
        if (ws == null) {
            return " (the model does not allow " + names.getOrDefault(channel, "it") + " at all before "
                    + (hasDeadline() ? "the next deadline" : "the end of the test") + ")";
        }
        boolean early = ws.stream().allMatch(w -> atTicks < w.lo());
        boolean late = ws.stream().allMatch(w -> atTicks > w.hi());
        return early ? " (too early)" : late ? " (too late)" : "";
    }

    private long micros(long ticks) {
        return ticks * unitMicros / semantics.ticksPerUnit();
    }

    private static List<Window> merge(List<Window> ws) {
        List<Window> sorted = new ArrayList<>(ws);
        sorted.sort((a, b) -> Long.compare(a.lo(), b.lo()));
        List<Window> out = new ArrayList<>();
        for (Window w : sorted) {
            if (!out.isEmpty() && w.lo() <= out.get(out.size() - 1).hi() + 1) {
                Window last = out.remove(out.size() - 1);
                out.add(new Window(last.lo(), Math.max(last.hi(), w.hi()), last.edge(), last.from(), last.move()));
            } else {
                out.add(w);
            }
        }
        return out;
    }

    /**
     * Why the environment cannot take output {@code channel} in {@code atTime} although the implementation can
     * send it (the sending edge), or null when the implementation cannot send it either.
     */
    public static String environmentRefuses(StateSet atTime, Semantics semantics, Partition partition,
                                            int channel) {
        for (SymState s : atTime.states()) {
            Semantics.Step send = semantics.enabledSend(s, channel, p -> !partition.isEnvironment(p));
            if (send != null) {
                boolean[] environment = new boolean[semantics.network().processes().size()];
                for (int p = 0; p < environment.length; p++) {
                    environment[p] = partition.isEnvironment(p);
                }
                return "the implementation may send it (" + semantics.describe(send)
                        + "), but no environment process can receive it in " + semantics.describe(s, environment);
            }
        }
        return null;
    }

    /** Microseconds as model time units with three decimals, e.g. {@code 135.002}. */
    public static String units(long micros, long unitMicros) {
        long whole = Math.floorDiv(micros, unitMicros);
        long rest = Math.floorMod(micros, unitMicros) * 1000 / unitMicros;
        return whole + "." + String.format("%03d", rest);
    }
}
