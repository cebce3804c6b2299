package io.dtron.engine.monitor;

import io.dtron.engine.Event;
import io.dtron.engine.TestOptions;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.clock.Reference;
import io.dtron.engine.internal.clock.Ticks;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.monitor.Tracker;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.StateText;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.verify.StateProperty;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.ClockVariable;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.math.BigDecimal;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.OptionalLong;
import java.util.function.Supplier;

/**
 * Watches a running system against a closed model: it is told every event on the model's observable channels
 * (inputs and outputs alike, {@link #observe} in time order) and the passing of time ({@link #advanceTo}), tracks
 * the symbolic states the model can be in, and raises an {@link Alarm} when an event is not allowed then, or when
 * time passes a deadline (the model required an event by then). It starts from the initial state at time 0, or,
 * not knowing the history, from every state the model can reach (or those a state property names) at the time of
 * the first call, and narrows as events come: so it raises no alarm that only the missing history explains. Stops
 * at the first violation unless told to go on; then it counts violations and re-synchronises after each one, from
 * every reachable state consistent with the violating event. Times are microseconds on the run's clock. Not
 * thread-safe: one thread feeds it.
 */
public final class Monitor {
    /** How far past a violation the alarm looks for what the model allowed: 100 time units. */
    private static final int WINDOW_HORIZON_UNITS = 100;
    /** The most allowed events an explanation names; the alarm lists them all. */
    private static final int DESCRIBED = 4;

    private final Network network;
    private final MonitorOptions options;
    private final long unit;
    private final int ticksPerUnit;
    private final Ticks ticks;
    private final Tracker tracker;
    private final Map<String, Channel> channels = new HashMap<>();
    private final List<Channel> byNumber = new ArrayList<>();
    private final String[] clockNames;
    /** Every reachable state (null until a re-synchronisation or an unknown-history start needs it). */
    private Tracker.Node reachable;
    private Tracker.Node current;
    private long lastMicros;
    /**
     * The time of the states' elapsed clock's 0: the start of the last event's window (its time rounded down to a
     * tick, less its clock error; the states keep when in the window it came), on the ticks of the start.
     */
    private Reference reference;
    private boolean started;
    private boolean stopped;
    /** Why the monitor could not follow the events further (null while it can). */
    private String gaveUp;
    /** What happened at {@link #lastMicros}: the start, the last event or a re-synchronisation. */
    private String since = "the start";
    private long events;
    private int violations;
    private Alarm first;

    /** An observable channel: its number, the state slots of its attached variables and their names. */
    private record Channel(String name, int channel, int[] slots, String[] variables, int[] values, boolean input) {
    }

    private Monitor(Network network, TestInterface testInterface, MonitorOptions options, boolean remember) {
        this.network = network;
        this.options = options;
        this.unit = options.timeUnitMicros();
        this.ticks = Ticks.of(unit);
        this.ticksPerUnit = ticks.perUnit();
        this.reference = Reference.at(ticks, 0);
        Semantics semantics = new Semantics(network, ticksPerUnit);
        boolean[] observed = new boolean[network.channelCount()];
        List<TestInterface.ObservableChannel> all = new ArrayList<>(testInterface.inputs());
        all.addAll(testInterface.outputs());
        for (TestInterface.ObservableChannel c : all) {
            if (c.name().equals(Alarm.CHANNEL)) {
                throw new UnsupportedModelException("the channel name '" + Alarm.CHANNEL + "' is reserved for the"
                        + " monitor's alarms");
            }
            observed[c.channel()] = true;
            int n = c.variables().size();
            int[] slots = new int[n];
            String[] names = new String[n];
            for (int i = 0; i < n; i++) {
                slots[i] = c.variables().get(i).variable().offset();
                names[i] = c.variables().get(i).name();
            }
            Channel ch = new Channel(c.name(), c.channel(), slots, names, new int[n],
                    testInterface.inputs().contains(c));
            channels.put(c.name(), ch);
            byNumber.add(ch);
        }
        this.tracker = new Tracker(semantics, observed, remember);
        this.clockNames = new String[semantics.dimension()];
        for (ClockVariable c : network.clocks()) {
            for (int i = c.index(); i < c.index() + c.type().clocks(); i++) {
                clockNames[i] = c.elementName(i);
            }
        }
    }

    /**
     * A monitor of the closed network {@code network} whose observable channels are those of {@code
     * testInterface}, inputs and outputs alike.
     *
     * @throws UnsupportedModelException when the engine cannot run the model, it names a channel {@link
     *                                   Alarm#CHANNEL}, or it has too many reachable states to start from all of them
     * @throws QueryException            when the start property does not compile or no reachable state satisfies it
     */
    public static Monitor of(Network network, TestInterface testInterface, MonitorOptions options) {
        return of(network, testInterface, options, true);
    }

    /** {@link #of}, remembering no transition when {@code remember} is false (for tests comparing both). */
    static Monitor of(Network network, TestInterface testInterface, MonitorOptions options, boolean remember) {
        Monitor m = new Monitor(network, testInterface, options, remember);
        try {
            switch (options.start()) {
                case INITIAL -> {
                    m.current = m.tracker.node(List.of(m.tracker.semantics().initial()));
                    m.started = true;
                }
                case ANY -> m.current = m.reachable();
                case FROM -> {
                    StateProperty p = StateProperty.goal(network, Query.parse("E<> " + options.from()), m.ticksPerUnit);
                    m.current = m.tracker.reachable(p::holdsSomewhere);
                    if (m.current.isEmpty()) {
                        throw new QueryException("no reachable state of the model satisfies '" + options.from() + "'");
                    }
                }
                default -> throw new IllegalStateException(options.start().toString());
            }
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while exploring the model's states: " + e.format());
        } catch (UnsupportedModelException e) {
            throw new UnsupportedModelException(e.getMessage() + ": start from the initial state");
        }
        return m;
    }

    private Tracker.Node reachable() {
        if (reachable == null) {
            reachable = tracker.reachable(s -> true);
        }
        return reachable;
    }

    /**
     * Observes {@code event} at {@code micros}: null when the model allows it then, else the alarm (counted; the
     * monitor stops unless it goes on after violations). Ignored once the monitor has stopped.
     *
     * @throws IllegalArgumentException when the event's channel is not an observable channel of the model, its
     *                                  variables are not those attached to the channel, or it comes before the last
     *                                  event; the monitor is unchanged then
     * @throws UnsupportedModelException on a model error or a model too nondeterministic to follow
     */
    public Alarm observe(Event event, long micros) {
        return observe(event, micros, 0);
    }

    /**
     * {@link #observe(Event, long)} of an event whose time is known give or take {@code uncertaintyMicros} (the
     * clock error of whoever stamped it): it is allowed when the model allows it at some time of that window (but
     * not before the last event).
     *
     * @throws IllegalArgumentException as {@link #observe(Event, long)} does, and for a negative uncertainty
     */
    public Alarm observe(Event event, long micros, long uncertaintyMicros) {
        return observe(event, micros, uncertaintyMicros, false);
    }

    /**
     * A shield's check of an event it may still withhold: as {@link #observe(Event, long, long)} when the model
     * allows the event (it is observed, null), else the alarm (counted), with the monitor's states unchanged, since
     * the withheld event did not happen; the monitor goes on either way.
     *
     * @throws IllegalArgumentException as {@link #observe(Event, long, long)} does
     */
    public Alarm withhold(Event event, long micros, long uncertaintyMicros) {
        return observe(event, micros, uncertaintyMicros, true);
    }

    private Alarm observe(Event event, long micros, long uncertaintyMicros, boolean withholding) {
        if (uncertaintyMicros < 0) {
            throw new IllegalArgumentException("negative uncertainty " + uncertaintyMicros);
        }
        if (stopped) {
            return null;
        }
        Channel ch = channels.get(event.channel());
        if (ch == null) {
            throw new IllegalArgumentException("'" + event.channel() + "' is not an observable channel of the model");
        }
        Map<String, Integer> values = event.values();
        if (values.size() != ch.slots.length) {
            throw new IllegalArgumentException(badValues(ch, event));
        }
        for (int i = 0; i < ch.slots.length; i++) {
            Integer v = values.get(ch.variables[i]);
            if (v == null) {
                throw new IllegalArgumentException(badValues(ch, event));
            }
            ch.values[i] = v;
        }
        start(micros);
        if (micros < lastMicros) {
            throw new IllegalArgumentException("event " + event + " at " + time(micros) + " comes before the last one,"
                    + " at " + time(lastMicros));
        }
        long fromTicks = reference.windowStart(micros - uncertaintyMicros);
        // a window past what DTRON can time (a tolerance near its maximum) reaches as far as the zones tell
        long toTicks = Math.min(reference.ceil(Math.min(micros + uncertaintyMicros, TestOptions.MAX_DURATION_MICROS)),
                Bound.MAX_VALUE);
        events++;
        Tracker.Node next;
        try {
            next = tracker.step(current, ch.channel, ch.slots, ch.values, fromTicks, toTicks, true);
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while following " + event + ": " + e.format());
        }
        if (!next.isEmpty()) {
            current = next;
            lastMicros = micros;
            // the states keep when in the window (a tick, and the clock error) the event came, as the tester's do:
            // their time is the window's start, on the same ticks, so that no rounding adds up
            reference = reference.plus(fromTicks);
            since = "the last event";
            return null;
        }
        Alarm alarm = violation(event, ch, micros, fromTicks, toTicks);
        if (withholding) {
            stopped = false; // the event did not happen: the states and times stay as they were
            return alarm;
        }
        if (options.keepGoing()) {
            resynchronise(() -> {
                Tracker.Node consistent = tracker.step(reachable(), ch.channel, ch.slots, ch.values, 0, 0, false);
                return consistent.isEmpty() ? reachable() : consistent;
            }, micros);
        }
        return alarm;
    }

    /**
     * Lets time pass to {@code micros} without an event: null while the model allows it, else the alarm of the
     * deadline it passed (its time is the deadline's). A time before the last event's is ignored.
     *
     * @throws UnsupportedModelException on a model error or a model too nondeterministic to follow
     */
    public Alarm advanceTo(long micros) {
        if (stopped) {
            return null;
        }
        start(micros);
        if (micros <= lastMicros) {
            return null;
        }
        long elapsed = reference.floor(micros);
        try {
            if (tracker.allows(current, elapsed)) {
                return null;
            }
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while letting time pass: " + e.format());
        }
        List<SymState> reach = tracker.reach(current, elapsed);
        long deadlineTicks = Bound.value(tracker.latest(reach));
        long deadline = reference.micros(deadlineTicks);
        String explanation = "no event by " + time(deadline) + ", the deadline after " + since() + ": the model "
                + "required one of " + describe(required(allowed(elapsed), deadlineTicks)) + " by then";
        Alarm alarm = raise(Alarm.Reason.DEADLINE_MISSED, deadline, null, explanation, elapsed);
        if (options.keepGoing()) {
            resynchronise(this::reachable, deadline);
        }
        return alarm;
    }

    /**
     * Whether the model lets time pass to {@code micros} without an event (no deadline passes by then, or the
     * monitor has not started or has stopped); the monitor is unchanged, so that a live monitor can make sure no
     * event before {@code micros} is still on its way before it lets time pass ({@link #advanceTo}).
     *
     * @throws UnsupportedModelException on a model error
     */
    public boolean allowsTimeTo(long micros) {
        if (stopped || !started || micros <= lastMicros) {
            return true;
        }
        try {
            return tracker.allows(current, reference.floor(micros));
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while letting time pass: " + e.format());
        }
    }

    /**
     * The deadline the model sets after the last event: the latest time it lets pass without an event, when it
     * requires one by then; empty when it lets time pass without end (as far as the monitor can time), or the
     * monitor has not started or has stopped. The monitor is unchanged: of a recorded run whose end is not known, a
     * deadline still pending at its last event is one the run showed neither met nor missed.
     *
     * @throws UnsupportedModelException on a model error or a model too nondeterministic to follow
     */
    public OptionalLong pendingDeadline() {
        if (stopped || !started) {
            return OptionalLong.empty();
        }
        int latest;
        try {
            latest = tracker.latest(tracker.reach(current, Bound.MAX_VALUE));
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while letting time pass: " + e.format());
        }
        if (latest == Bound.INFINITY || Bound.value(latest) >= Bound.MAX_VALUE) {
            return OptionalLong.empty();
        }
        return OptionalLong.of(reference.micros(Bound.value(latest)));
    }

    /** Returns the time of the last event the monitor accepted (or of its start, or re-synchronisation). */
    public long lastMicros() {
        return lastMicros;
    }

    /**
     * Forgets what the events so far said: the monitor starts again from every state the model can reach, at the
     * time of the next event or tick, as after an event it could not read (so that the missing event raises no
     * alarm). Ignored once the monitor has stopped.
     */
    public void forgetHistory() {
        if (stopped) {
            return;
        }
        try {
            current = reachable();
        } catch (UnsupportedModelException e) {
            giveUp("it cannot start again from every reachable state after a gap in the events: " + e.getMessage());
            return;
        }
        started = false;
        since = "the gap in the events";
    }

    /**
     * Goes on after a violation from {@code states} at {@code micros}, or stops following the events when they are
     * too many to start again from.
     */
    private void resynchronise(Supplier<Tracker.Node> states, long micros) {
        try {
            current = states.get();
        } catch (UnsupportedModelException e) {
            giveUp("it cannot re-synchronise after violation " + violations + ": " + e.getMessage());
            return;
        }
        lastMicros = micros;
        reference = Reference.at(ticks, micros);
        since = "the re-synchronisation";
    }

    /** Stops following the events, for {@code why}: what the monitor judged so far stands. */
    private void giveUp(String why) {
        stopped = true;
        gaveUp = why;
    }

    /**
     * Why the monitor stopped following the events before their end, when it could not go on (a model with too
     * many reachable states to start again from all of them, after a violation with {@code --continue} or a gap
     * in the events); empty while it follows them, or when it stopped at a violation.
     */
    public Optional<String> gaveUp() {
        return Optional.ofNullable(gaveUp);
    }

    private void start(long micros) {
        if (!started) {
            started = true;
            lastMicros = micros;
            reference = Reference.at(ticks, micros);
        }
    }

    private Alarm violation(Event event, Channel ch, long micros, long fromTicks, long toTicks) {
        Tracker.Node atTime = tracker.afterWindow(current, fromTicks, toTicks, false);
        if (atTime.isEmpty()) {
            long deadlineTicks = Bound.value(tracker.latest(tracker.reach(current, toTicks)));
            long deadline = reference.micros(deadlineTicks);
            String explanation = "no event by " + time(deadline) + ", the deadline after " + since() + ": the model "
                    + "required one of " + describe(required(allowed(toTicks), deadlineTicks)) + " by then; the next"
                    + " event, " + event
                    + ", came at " + time(micros);
            return raise(Alarm.Reason.DEADLINE_MISSED, deadline, event, explanation, toTicks);
        }
        List<SymState> targets = new ArrayList<>();
        List<Semantics.Move> moves = tracker.moves(atTime, ch.channel, targets);
        if (!moves.isEmpty()) {
            List<String> values = new ArrayList<>();
            for (SymState t : targets) {
                String v = valuesOf(ch, t).toString();
                if (!values.contains(v)) {
                    values.add(v);
                }
            }
            String explanation = event + " at " + time(micros) + " carries values the model does not allow then: it"
                    + " allowed " + ch.name + " with " + String.join(" or ", values) + " ("
                    + tracker.semantics().describe(moves.get(0).steps().get(0)) + ")";
            return raise(Alarm.Reason.WRONG_VALUES, micros, event, explanation, toTicks);
        }
        String explanation = event + " at " + time(micros) + " is not allowed then: after " + since()
                + " the model allowed " + describe(allowed(toTicks));
        return raise(Alarm.Reason.UNEXPECTED_EVENT, micros, event, explanation, toTicks);
    }

    private Alarm raise(Alarm.Reason reason, long micros, Event event, String explanation, long ticks) {
        violations++;
        List<Alarm.State> states = new ArrayList<>();
        for (SymState s : current.states()) {
            if (states.size() == Alarm.MAX_STATES) {
                break;
            }
            states.add(describe(s));
        }
        Alarm alarm = new Alarm(violations, reason, micros, event, explanation, lastMicros, allowed(ticks), states,
                current.states().size() - states.size());
        if (first == null) {
            first = alarm;
        }
        stopped = !options.keepGoing();
        return alarm;
    }

    private String since() {
        return since + " at " + time(lastMicros);
    }

    /**
     * The events the model allowed after the last one, up to {@code upTo} ticks after it and some way beyond, with
     * their windows: per channel and values, the earliest and latest time.
     */
    private List<Alarm.Window> allowed(long upTo) {
        List<SymState> reach;
        long horizon = 2 * upTo + (long) WINDOW_HORIZON_UNITS * ticksPerUnit;
        try {
            reach = tracker.reach(current, horizon);
        } catch (UnsupportedModelException e) {
            horizon = upTo;
            reach = tracker.reach(current, horizon);
        }
        long end = Math.min(horizon, Bound.MAX_VALUE);
        Map<String, long[]> windows = new LinkedHashMap<>();
        Map<String, Alarm.Window> keys = new LinkedHashMap<>();
        int elapsed = tracker.semantics().elapsedClock();
        for (Channel ch : byNumber) {
            for (SymState s : reach) {
                tracker.observableMoves(s, ch.channel, (move, t) -> {
                    Map<String, Integer> values = valuesOf(ch, t);
                    String key = ch.name + values;
                    Dbm z = t.zone();
                    long lo = -Bound.value(z.upperBound(0, elapsed));
                    int upper = z.upperBound(elapsed, 0);
                    // a window open at the horizon is open as far as this looked: said as without end
                    long hi = upper == Bound.INFINITY || Bound.value(upper) >= end ? -1 : Bound.value(upper);
                    long[] w = windows.get(key);
                    if (w == null) {
                        windows.put(key, new long[] {lo, hi});
                        keys.put(key, new Alarm.Window(ch.name, values, 0, 0));
                    } else {
                        w[0] = Math.min(w[0], lo);
                        w[1] = w[1] < 0 || hi < 0 ? -1 : Math.max(w[1], hi);
                    }
                });
            }
        }
        List<Alarm.Window> out = new ArrayList<>();
        for (Map.Entry<String, long[]> e : windows.entrySet()) {
            long[] w = e.getValue();
            Alarm.Window k = keys.get(e.getKey());
            out.add(new Alarm.Window(k.channel(), k.values(), reference.microsFloor(w[0]),
                    w[1] < 0 ? -1 : reference.micros(w[1])));
        }
        return out;
    }

    /**
     * Of the events the model allowed, those a missed deadline ({@code deadlineTicks} after the last event) required:
     * every output, and the inputs after which time may pass beyond the deadline (an input that leaves it where it
     * was would not have met it); all of them if that leaves none.
     */
    private List<Alarm.Window> required(List<Alarm.Window> allowed, long deadlineTicks) {
        List<Alarm.Window> required = new ArrayList<>();
        for (Alarm.Window w : allowed) {
            Channel ch = channels.get(w.channel());
            if (!ch.input || liftsDeadline(ch, w, deadlineTicks)) {
                required.add(w);
            }
        }
        return required.isEmpty() ? allowed : required;
    }

    /** Whether time may pass beyond the deadline after the event of {@code w}, some time in its window before it. */
    private boolean liftsDeadline(Channel ch, Alarm.Window w, long deadlineTicks) {
        long from = reference.windowStart(w.fromMicros());
        if (from > deadlineTicks) {
            return false;
        }
        int[] values = new int[ch.slots.length]; // not ch.values: the violating event's, which going on uses
        for (int i = 0; i < values.length; i++) {
            values[i] = w.values().get(ch.variables[i]);
        }
        Tracker.Node after = tracker.step(current, ch.channel, ch.slots, values, from, deadlineTicks, true);
        return !after.isEmpty() && tracker.allows(after, deadlineTicks - from + 1);
    }

    private String describe(List<Alarm.Window> allowed) {
        if (allowed.isEmpty()) {
            return "no event";
        }
        List<String> parts = new ArrayList<>();
        for (Alarm.Window w : allowed) {
            if (parts.size() == DESCRIBED) {
                parts.add("and " + (allowed.size() - DESCRIBED) + " more");
                break;
            }
            parts.add(new Event(w.channel(), w.values()) + " in [" + time(w.fromMicros()) + ", "
                    + (w.toMicros() < 0 ? "t=inf)" : time(w.toMicros()) + "]"));
        }
        return String.join(", ", parts);
    }

    private Map<String, Integer> valuesOf(Channel ch, SymState s) {
        Map<String, Integer> values = new LinkedHashMap<>();
        for (int i = 0; i < ch.slots.length; i++) {
            values.put(ch.variables[i], s.var(ch.slots[i]));
        }
        return values;
    }

    private static String badValues(Channel ch, Event event) {
        return "event " + event + ": the model attaches " + java.util.Arrays.toString(ch.variables) + " to '" + ch.name
                + "', the event carries " + event.values().keySet();
    }

    private Alarm.State describe(SymState s) {
        List<String> locations = StateText.locations(network, s);
        Map<String, Integer> variables = StateText.variables(network, s);
        List<String> clocks = new ArrayList<>();
        Dbm z = s.zone();
        for (int x = 1; x < clockNames.length - 1; x++) {
            int lower = z.upperBound(0, x);
            int upper = z.upperBound(x, 0);
            clocks.add(clockNames[x] + " in " + (Bound.isStrict(lower) ? "(" : "[") + units(-Bound.value(lower)) + ", "
                    + (upper == Bound.INFINITY ? "inf)" : units(Bound.value(upper)) + (Bound.isStrict(upper) ? ")" : "]")));
        }
        return new Alarm.State(locations, variables, String.join(", ", clocks));
    }

    private String units(long ticks) {
        return BigDecimal.valueOf(ticks).divide(BigDecimal.valueOf(ticksPerUnit)).stripTrailingZeros().toPlainString();
    }

    /** The number of violations so far. */
    public int violations() {
        return violations;
    }

    /** The number of events observed so far. */
    public long events() {
        return events;
    }

    /** How many events were answered from a remembered transition (for tests). */
    long recalled() {
        return tracker.recalled();
    }

    /** The first alarm, or null while there is none. */
    public Alarm firstAlarm() {
        return first;
    }

    /**
     * Whether the monitor has stopped: at a violation (it does not go on after violations), or because it could not
     * follow the events further ({@link #gaveUp}).
     */
    public boolean stopped() {
        return stopped;
    }

    /** The options. */
    public MonitorOptions options() {
        return options;
    }

    private String time(long micros) {
        return ticks.time(micros);
    }
}
