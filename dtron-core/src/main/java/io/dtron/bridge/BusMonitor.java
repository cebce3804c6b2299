package io.dtron.bridge;

import io.dtron.api.Dtron;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.internal.TesterSide;
import io.dtron.bridge.internal.ReorderWindow;
import io.dtron.bridge.internal.RunTimeline;
import io.dtron.engine.Event;
import io.dtron.engine.monitor.Alarm;
import io.dtron.engine.monitor.Monitor;
import io.dtron.engine.monitor.MonitorOptions;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.PriorityQueue;
import java.util.Set;
import java.util.TreeSet;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The monitor's role in a run on a DTRON bus ({@code dtron monitor --cluster/--bus}): a passive member that observes
 * every channel of the model (inputs and outputs alike, whoever publishes them) without serving any, puts the events
 * in order by their event times on the run's clock (the times the tester judges by: a sender's stamp corrected by its
 * clock offset, an input where its adapter's acknowledgement places it; {@link RunTimeline}) within the reorder window
 * ({@link ReorderWindow}, fixed or automatic), and feeds them to a {@link Monitor} on a thread of its own. That thread
 * also lets time pass on the run's clock, so a missed deadline is found when the deadline is a reorder window old,
 * not at the next message, and once the members that send the model's outputs answered its probe, as the tester's
 * before it declares a deadline missed ({@link TesterSide#probe}), or a second passed. The run's id and time 0 come
 * from the tester's {@link Dtron#RUN_START}: at each, the monitor starts again (from the options' start); a monitor
 * that joins during a run starts at once. Time passes for
 * the monitor from the run's start or from the first event it sees, so a system that has not started yet raises no
 * alarm.
 *
 * <p>The watch follows successive runs: a run's watch ends at the tester's {@link Dtron#RUN_STOP} (once every event
 * before it was judged), at the monitor's first violation unless it goes on after violations, or at the next run's
 * start; the monitor then reports that run ({@link Sink#runEnded}) and waits for the next run's start. The watch ends
 * after {@link Settings#runs} runs, or at {@link #finish}.
 *
 * <p>The monitor judges a run up to the instant the tester did: the stop's event time is the end of the tester's
 * observation (its timeout, or its verdict's time when that came first), and the start announces the run's end (the
 * timeout; {@link IDtronChannelValued#getEndTimeNanos()}; a monitor that joined during the run learns it from the
 * tester's answers to its clock pings, {@link TesterSide#announcedEnd}), beyond which the monitor lets no time pass
 * while it waits for the stop. Events stamped after the end are not judged but counted ({@link RunResult#afterEnd});
 * an event stamped before it is judged even if it arrives after the stop. As the tester, the monitor judges the events
 * at the end itself, and a deadline only when the instant past it lies before the end. A tester that announces no end
 * (an older one, a run of several testers) stamps its stop when it publishes it: the run ends there.
 *
 * <p>Each alarm and each run's verdict are published on {@link Dtron#ALARM}, stamped with the run's id. A shield
 * ({@link Settings#shield})
 * judges the messages of one channel as they arrive and republishes those the model allows on another channel, for
 * the consumers; those it forbids are withheld, which the alarm says.
 */
public final class BusMonitor implements AutoCloseable {
    private static final Logger LOG = LoggerFactory.getLogger(BusMonitor.class);
    /** How long the monitor waits, when it joins, for its clock's offset to a tester on the bus. */
    static final Duration OFFSET_TIMEOUT = Duration.ofSeconds(2);
    /**
     * How long the monitor waits for the adapters' answers to its probe before it lets a deadline pass, as the tester
     * does; then it judges without them.
     */
    static final Duration PROBE_TIMEOUT = Duration.ofSeconds(1);
    /** How long the monitor waits for its listeners to catch up before it lets a deadline pass. */
    static final Duration CATCH_UP_TIMEOUT = Duration.ofSeconds(1);
    /**
     * How long a tester's input waits at most for the acknowledgement that places it where its adapter applied it;
     * then it is taken as happened when the tester published it.
     */
    static final Duration ACK_TIMEOUT = Duration.ofSeconds(2);
    /** The longest the monitor's thread sleeps between two looks at the clock. */
    private static final long TICK_MAX_MICROS = 10_000;

    /** What the monitor does and how it orders events. */
    public record Settings(long windowMicros, boolean automaticWindow, long toleranceMicros, String shield,
            String shielded, int runs) {
        /**
         * @param windowMicros    the reorder window the monitor starts with (at least 0)
         * @param automaticWindow whether it widens when a message takes more than half of it
         * @param toleranceMicros each event's time give or take this, beyond its sender's clock error
         * @param shield          the channel the monitor shields, or null
         * @param shielded        the channel it republishes the allowed messages of {@code shield} on, or null
         * @param runs            how many runs the watch follows before it ends; 0: every run, until {@link
         *                        BusMonitor#finish}
         */
        public Settings {
            if (windowMicros < 0 || toleranceMicros < 0 || runs < 0) {
                throw new IllegalArgumentException("negative window, tolerance or runs");
            }
            if ((shield == null) != (shielded == null)) {
                throw new IllegalArgumentException("a shield needs both channels");
            }
        }
    }

    /** Makes the monitor of a watch. */
    @FunctionalInterface
    public interface Monitors {
        /**
         * The monitor when the watch starts ({@code runTimeUnitMicros} 0; null: none, the watch begins at the next
         * run start), or at a run start, whose time unit the tester's start message says.
         */
        Monitor make(long runTimeUnitMicros);
    }

    /** Told, on the monitor's thread, what the monitor finds. */
    public interface Sink {
        /** A run started on the bus (a tester's run start, with the run's time unit); the monitor starts again. */
        void runStarted(String runId, long timeUnitMicros);

        /**
         * An alarm.
         *
         * @param withheld whether the shield withheld the violating message
         */
        void alarm(Alarm alarm, boolean withheld);

        /** A run's watch ended (its verdict was published on {@link Dtron#ALARM}); the monitor waits for the next. */
        void runEnded(RunResult run);

        /** Something worth a line: a message that came too late for the window, a widened window. */
        void note(String line);
    }

    /** Why a run's watch ended. */
    public enum End {
        /** The run's stop came, and every event before it was judged. */
        STOPPED,
        /** The monitor stopped at the run's first violation (it does not go on after violations). */
        FIRST_VIOLATION,
        /** Another run started before this one's stop came. */
        NEXT_RUN,
        /** The watch ended ({@link BusMonitor#finish}, or an error) before the run's stop. */
        WATCH_ENDED,
        /**
         * The monitor could not follow the run further (after a message too late to judge, a model with too many
         * reachable states to start again from all of them): the rest of the run was not judged.
         */
        GAVE_UP
    }

    /**
     * One run's watch, with its counts.
     *
     * @param runId    the run's id ("" when no message named one: a system watched without a tester)
     * @param withheld the messages the shield withheld, with those of the time before the run since the last one
     * @param afterEnd the events of the run stamped after its end (the tester's end of observation, or the end its
     *                 start announced), which were not judged
     * @param firstAlarm the run's first violation, or null when it had none
     */
    public record RunResult(String runId, int violations, long events, long late, long withheld, End end,
            long afterEnd, Alarm firstAlarm) {
    }

    /**
     * How far the watch is, for a progress line; read on any thread ({@link #progress}).
     *
     * @param runId          the run watched ("" when no message named one: a system watched without a tester)
     * @param watching       whether a monitor watches now (false between runs, waiting for a run's start)
     * @param judgedToMicros the time up to which the run was judged, on its clock; negative before anything was
     * @param runsEnded      how many runs' watches ended before this one
     */
    public record Progress(String runId, boolean watching, long judgedToMicros, long events, int violations, long late,
            long withheld, int runsEnded) {
    }

    /** How the watch ended: the runs it watched, in order, and the error that stopped it, or null. */
    public record Result(List<RunResult> runs, String error) {
        /** Copies the runs. */
        public Result {
            runs = List.copyOf(runs);
        }

        /** The violations of all runs. */
        public int violations() {
            return runs.stream().mapToInt(RunResult::violations).sum();
        }

        /** The events of all runs. */
        public long events() {
            return runs.stream().mapToLong(RunResult::events).sum();
        }

        /** The messages of all runs that came too late to be judged. */
        public long late() {
            return runs.stream().mapToLong(RunResult::late).sum();
        }

        /** The messages the shield withheld in all runs. */
        public long withheld() {
            return runs.stream().mapToLong(RunResult::withheld).sum();
        }

        /** The events of all runs stamped after their runs' ends, not judged. */
        public long afterEnd() {
            return runs.stream().mapToLong(RunResult::afterEnd).sum();
        }
    }

    private final Dtron dtron;
    /** The bus member's machinery this role shares with the tester's (catching up with the listeners). */
    private final TesterSide tester;
    private final Monitors monitors;
    private final Settings settings;
    private final Sink sink;
    /** The channels of the model by name, with their 1-based position for the alarm message. */
    private final Map<String, Integer> positions = new LinkedHashMap<>();
    /** The inputs of the model, by name. */
    private final java.util.Set<String> inputNames = new java.util.HashSet<>();
    private final BlockingQueue<Object> arrivals = new LinkedBlockingQueue<>();
    private final RunTimeline timeline;
    private final ReorderWindow window = new ReorderWindow();
    private final CountDownLatch ended = new CountDownLatch(1);
    private final IDtronChannel shieldedChannel;
    private volatile Result result;
    private volatile Progress progress = new Progress("", false, -1, 0, 0, 0, 0, 0);
    private Thread worker;

    /** An event on a model channel, held until it is a reorder window old. */
    private static final class Held implements Comparable<Held> {
        final IDtronChannelValued message;
        long micros;
        long errorMicros;
        final long order;
        /** A tester's input, which waits (until {@link #ackDeadline}) for the acknowledgement that places it. */
        boolean awaitingAck;
        long ackDeadline;

        Held(IDtronChannelValued message, long micros, long errorMicros, long order) {
            this.message = message;
            this.micros = micros;
            this.errorMicros = errorMicros;
            this.order = order;
        }

        @Override
        public int compareTo(Held o) {
            return micros != o.micros ? Long.compare(micros, o.micros) : Long.compare(order, o.order);
        }
    }

    /** What the listeners' thread hands the monitor's thread, in the bus's order. */
    private record Arrival(String kind, IDtronChannelValued message) {
    }

    private BusMonitor(Dtron dtron, TestInterface testInterface, Monitors monitors, Settings settings,
            Sink sink) {
        this.dtron = dtron;
        this.tester = TesterSide.of(dtron);
        this.monitors = monitors;
        this.settings = settings;
        this.sink = sink;
        this.timeline = new RunTimeline(dtron::currentTimeNanos);
        window.set(settings.windowMicros(), settings.automaticWindow());
        testInterface.inputs().forEach(c -> inputNames.add(c.name()));
        List<TestInterface.ObservableChannel> all = new ArrayList<>(testInterface.inputs());
        all.addAll(testInterface.outputs());
        Map<String, IDtronChannel> channels = new LinkedHashMap<>();
        for (TestInterface.ObservableChannel c : all) {
            if (Dtron.isReservedChannel(c.name())) {
                throw new IllegalArgumentException("channel '" + c.name() + "' of the model's interface has a name"
                        + " DTRON reserves; rename it");
            }
            positions.putIfAbsent(c.name(), positions.size() + 1);
            channels.putIfAbsent(c.name(), IDtronChannel.of(c.name(), c.variables().stream()
                    .map(TestInterface.AttachedVariable::name).toList()));
        }
        if (settings.shield() != null) {
            IDtronChannel shield = channels.get(settings.shield());
            if (shield == null) {
                throw new IllegalArgumentException("--shield " + settings.shield() + ": not a channel of the model's"
                        + " interface (" + String.join(", ", channels.keySet()) + ")");
            }
            if (channels.containsKey(settings.shielded()) || Dtron.isReservedChannel(settings.shielded())) {
                throw new IllegalArgumentException("--shield: the shielded channel '" + settings.shielded()
                        + "' is a channel of the model or DTRON's own");
            }
            this.shieldedChannel = IDtronChannel.of(settings.shielded(), shield.getVariableNames());
            dtron.declareOutputs(shieldedChannel);
        } else {
            this.shieldedChannel = null;
        }
        for (IDtronChannel channel : channels.values()) {
            boolean shielding = channel.getChannelName().equals(settings.shield());
            dtron.addDtronListener(new DtronListener(channel) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    arrivals.add(new Arrival(shielding ? "shield" : "event", message));
                }

                @Override
                protected boolean autoAcknowledge() {
                    return false; // the monitor observes; a shield's consumers apply what it republishes
                }

                @Override
                protected boolean serves() {
                    return shielding; // the shield is its channel's consumer on the bus
                }
            });
        }
        for (IDtronChannel reserved : List.of(Dtron.RUN_START, Dtron.RUN_STOP, Dtron.ACK)) {
            dtron.addDtronListener(new DtronListener(reserved) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    arrivals.add(new Arrival(reserved.getChannelName(), message));
                }
            });
        }
    }

    /**
     * Joins the bus as a monitor of the closed model whose observable channels are {@code testInterface}'s, and
     * starts watching: the first run start on the bus, or the first event, starts the monitor's clock.
     *
     * @param monitors makes the {@link Monitor} when the watch starts and at every run start
     * @throws IllegalArgumentException if a channel of the interface cannot be a bus channel, or the shield's are
     *                                  not as {@link Settings} says
     * @throws DtronException           if the bus cannot be joined
     */
    public static BusMonitor connect(TestInterface testInterface, Monitors monitors, Settings settings,
            DtronOptions.Builder options, Sink sink) {
        Objects.requireNonNull(sink, "sink");
        Dtron dtron = Dtron.connect(options.build());
        BusMonitor m;
        try {
            m = new BusMonitor(dtron, testInterface, monitors, settings, sink);
        } catch (RuntimeException e) {
            dtron.close();
            throw e;
        }
        m.worker = new Thread(m::watch, "dtron-monitor");
        m.worker.setDaemon(true);
        m.worker.start();
        return m;
    }

    /** How far the watch is now: what the monitor's thread last judged. */
    public Progress progress() {
        return progress;
    }

    /** Returns this member's id on the bus. */
    public String memberId() {
        return dtron.getMemberId();
    }

    /**
     * Waits until the watch ended: the last of {@link Settings#runs} runs ended (its {@link Dtron#RUN_STOP} came and
     * every event before it was judged, or the monitor stopped at its first violation unless it goes on after
     * violations); {@code timeout} at most.
     *
     * @return the result, or null if the run did not end within the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public Result await(Duration timeout) throws InterruptedException {
        return ended.await(timeout.toNanos(), TimeUnit.NANOSECONDS) ? result : null;
    }

    /**
     * Ends the watch now (the monitor's time), judges what it holds and publishes the verdict of the run it watched;
     * returns the result. Returns the result at once if the watch had ended.
     *
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public Result finish() throws InterruptedException {
        arrivals.add(new Arrival("finish", null));
        ended.await();
        return result;
    }

    /** Leaves the bus (ending the watch first, if it goes on); closing twice does nothing. */
    @Override
    public void close() {
        if (ended.getCount() > 0) {
            arrivals.add(new Arrival("finish", null));
            try {
                ended.await(5, TimeUnit.SECONDS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
        dtron.close();
    }

    // ---- the monitor's thread ----

    private Monitor monitor;
    private final PriorityQueue<Held> held = new PriorityQueue<>();
    /** The inputs held, by sender/sequence, until an acknowledgement places them. */
    private final Map<String, Held> inputs = new HashMap<>();
    private long order;
    /** The run's id once a run start was seen or a message carried one; "" before. */
    private String runId = "";
    /** Time passes for the monitor from here: the run's start, or the first event's time (none before). */
    private long clockStart = Long.MAX_VALUE;
    /** The time up to which the monitor judged, on the run's clock. */
    private long judgedTo = Long.MIN_VALUE;
    /** The end of the run, on the run's clock, once its stop came; else none. */
    private long stopAt = Long.MAX_VALUE;
    /** The end of the run its start announced, on the run's clock; none when it announced none. */
    private long endAt = Long.MAX_VALUE;
    /** The counts of the run watched (or, between runs, of the time since the last one). */
    private int violations;
    private long events;
    private long late;
    private long withheld;
    private long afterEnd;
    /** Whether the run watched began with a run start. */
    private boolean startSeen;
    private final List<RunResult> runs = new ArrayList<>();
    private String error;
    /** Whether the watch was told to end ({@link #finish}). */
    private boolean finishing;
    /** Whether the watch is over: told to end, or its last run ended. */
    private boolean done;

    private void watch() {
        try {
            if (dtron.getTester().isPresent()) {
                awaitOffset();
            }
            // time 0 until a run start says otherwise: now, on the tester's clock
            timeline.startedAt(nowTesterNanos(), 0);
            monitor = monitors.make(0);
            while (!done) {
                Object next = arrivals.poll(waitMicros(), TimeUnit.MICROSECONDS);
                if (next != null) {
                    take((Arrival) next);
                    drain();
                }
                if (done) {
                    break;
                }
                long now = nowMicros();
                if (finishing) {
                    judgeBefore(Math.min(now - window.micros(), end()));
                    break;
                }
                if (monitor == null) {
                    continue; // between runs
                }
                if (stopAt != Long.MAX_VALUE && now - window.micros() >= end()) {
                    judgeBefore(end());
                    endRun(End.STOPPED);
                    continue;
                }
                learnAnnouncedEnd();
                judgeBefore(Math.min(now - window.micros(), endAt));
                if (monitor.stopped()) {
                    endRun(stoppedAs(monitor));
                }
                showProgress();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            error = "interrupted";
        } catch (RuntimeException e) {
            LOG.warn("The monitor stopped", e);
            error = e.getMessage() == null ? e.toString() : e.getMessage();
        }
        if (!done && (watchedSomething() || runs.isEmpty())) {
            endRun(End.WATCH_ENDED);
        }
        result = new Result(runs, error);
        ended.countDown();
    }

    /** Shows the other threads how far the watch is ({@link #progress}). */
    private void showProgress() {
        progress = new Progress(runId, monitor != null, judgedTo == Long.MIN_VALUE ? -1 : judgedTo, events,
                violations, late, withheld, runs.size());
    }

    /**
     * Whether the run watched (or the time since the last one) has anything to report: events it held and has not
     * judged yet count, so that a run start that comes before they are a reorder window old ends the watch with them
     * judged, as it would a moment later, instead of dropping them.
     */
    private boolean watchedSomething() {
        return startSeen || !runId.isEmpty() || events > 0 || !held.isEmpty() || violations > 0 || late > 0
                || withheld > 0 || afterEnd > 0;
    }

    /** How a run ends whose monitor stopped: at its first violation, or because it could not follow it further. */
    private static End stoppedAs(Monitor monitor) {
        return monitor.gaveUp().isPresent() ? End.GAVE_UP : End.FIRST_VIOLATION;
    }

    /**
     * Ends the watch of a run: publishes its verdict, tells the sink, and waits for the next run's start (or ends the
     * watch after the last run).
     */
    private void endRun(End end) {
        End why = monitor != null && monitor.stopped() ? stoppedAs(monitor) : end;
        long last = end();
        afterEnd += held.stream().filter(h -> h.micros > last).count(); // held, then the stop came before them
        publishVerdict();
        RunResult run = new RunResult(runId, violations, events, late, withheld, why, afterEnd,
                monitor == null ? null : monitor.firstAlarm());
        runs.add(run);
        tester.setRunId("");
        monitor = null;
        held.clear();
        inputs.clear();
        runId = "";
        startSeen = false;
        clockStart = Long.MAX_VALUE;
        judgedTo = Long.MIN_VALUE;
        stopAt = Long.MAX_VALUE;
        endAt = Long.MAX_VALUE;
        violations = 0;
        events = 0;
        late = 0;
        withheld = 0;
        afterEnd = 0;
        done = settings.runs() > 0 && runs.size() >= settings.runs();
        showProgress();
        sink.runEnded(run);
    }

    /** The run watched is {@code id} from now on; the monitor's alarms and verdict carry it. */
    private void runIs(String id) {
        runId = id;
        tester.setRunId(id);
    }

    private void awaitOffset() throws InterruptedException {
        long deadline = System.nanoTime() + OFFSET_TIMEOUT.toNanos();
        while (!dtron.hasClockOffset() && System.nanoTime() < deadline) {
            Thread.sleep(5);
        }
    }

    /** This member's now on the tester's wall clock, in nanoseconds since the epoch. */
    private long nowTesterNanos() {
        return dtron.currentTimeNanos() + dtron.getClockOffsetNanos();
    }

    /** This member's now on the run's clock, in microseconds. */
    private long nowMicros() {
        return Math.floorDiv(nowTesterNanos() - timeline.zeroEpochNanos(), 1000);
    }

    /** How long to wait for the next arrival: until the first held event is due, at most a tick. */
    private long waitMicros() {
        long tick = Math.max(100, Math.min(TICK_MAX_MICROS, window.micros() / 10));
        Held first = held.peek();
        if (first == null) {
            return tick;
        }
        return Math.max(0, Math.min(tick, first.micros + window.micros() - nowMicros()));
    }

    /** Takes what arrived so far (until the watch is over). */
    private void drain() {
        for (Object next = done ? null : arrivals.poll(); next != null; next = done ? null : arrivals.poll()) {
            take((Arrival) next);
        }
    }

    private void take(Arrival a) {
        IDtronChannelValued m = a.message();
        switch (a.kind()) {
            case "finish" -> finishing = true;
            case "dtron_start" -> {
                if (m.getSender().equals(dtron.getMemberId())) {
                    return;
                }
                if (monitor != null && watchedSomething()) {
                    endWithHeld(stopAt != Long.MAX_VALUE ? End.STOPPED : End.NEXT_RUN);
                    if (done) {
                        return;
                    }
                }
                runIs(m.getRunId());
                startSeen = true;
                timeline.startedAt(m.getEventTimeNanos() + m.getClockOffsetNanos(), 0);
                held.clear();
                inputs.clear();
                monitor = monitors.make(m.getVariables().get("timeunit"));
                clockStart = 0;
                judgedTo = Long.MIN_VALUE;
                stopAt = Long.MAX_VALUE;
                endAt = m.getEndTimeNanos() == 0 ? Long.MAX_VALUE : Math.floorDiv(m.getEndTimeNanos()
                        + m.getClockOffsetNanos() - timeline.zeroEpochNanos(), 1000);
                sink.runStarted(runId, m.getVariables().get("timeunit"));
            }
            case "dtron_stop" -> {
                if (monitor != null && ofThisRun(m)) {
                    stopAt = timeline.eventMicros(m);
                }
            }
            case "dtron_ack" -> acknowledged(m);
            case "event" -> event(m);
            case "shield" -> shield(m);
            default -> throw new IllegalStateException(a.kind());
        }
    }

    /**
     * A run starts before the last one's end was judged: the events held of the last one are judged (in time order,
     * without waiting for acknowledgements, up to its stop or its last event), and its watch ends.
     */
    private void endWithHeld(End end) {
        held.forEach(h -> h.awaitingAck = false);
        if (stopAt != Long.MAX_VALUE) {
            judgeBefore(end());
        } else {
            long to = judgedTo;
            for (Held h : held) {
                to = Math.max(to, h.micros);
            }
            judge(to, to);
        }
        endRun(end);
    }

    /**
     * The end of the run watched on its clock: where the tester's observation ended, as its stop says, or else the
     * end its start announced; none ({@link Long#MAX_VALUE}) before a stop of a run that announced none.
     */
    private long end() {
        return Math.min(stopAt, endAt);
    }

    /**
     * Judges the held events up to {@code to} and lets time pass to it, but at the run's announced end ({@link
     * #endAt}): time passes only to just before it, so that a deadline is judged, as the tester judges it, only when
     * the instant past it lies before the end.
     */
    private void judgeBefore(long to) {
        judge(to, endAt != Long.MAX_VALUE && to >= end() ? to - 1 : to);
    }

    /** Whether a message belongs to the watched run: it carries its id, or none, or no run is known. */
    private boolean ofThisRun(IDtronChannelValued m) {
        if (runId.isEmpty() && !m.getRunId().isEmpty()) {
            runIs(m.getRunId()); // joined during a run: the first message that names one names it
        }
        return m.getRunId().isEmpty() || m.getRunId().equals(runId);
    }

    private void event(IDtronChannelValued m) {
        if (monitor == null || !ofThisRun(m)) {
            return;
        }
        // stamped before time 0 of a run whose start this monitor saw (ordered before it): from the start, as the
        // tester takes it
        long micros = startSeen ? Math.max(0, timeline.eventMicros(m)) : joined(timeline.eventMicros(m));
        if (micros > end()) {
            afterEnd++; // after the run's end; one before it that the bus ordered after the stop is the run's
            return;
        }
        clockStart = Math.min(clockStart, micros);
        widen(m, micros);
        Held h = new Held(m, micros, RunTimeline.errorMicros(m), order++);
        if (inputNames.contains(m.getChannelName()) && (m.getSender().equals(dtron.getTester().orElse(null))
                || tester.getOtherTesters().contains(m.getSender()))) {
            // a tester's input: its acknowledgement places it (no earlier than its stamp), so it is not late before
            // that says where (an adapter that applied the input before it applied this one a little after its
            // stamp moved the monitor past this one's stamp, not past its time)
            h.awaitingAck = true;
            h.ackDeadline = System.nanoTime() + ACK_TIMEOUT.toNanos();
        } else if (micros < monitor.lastMicros() && judgedTo != Long.MIN_VALUE) {
            late(h); // before an event the monitor judged: it cannot be placed
            return;
        }
        held.add(h);
        inputs.put(m.getSender() + "/" + m.getSequence(), h);
    }

    /**
     * The time of an event seen by a monitor that joined a running system ({@code micros} on its clock): while it has
     * judged nothing, an event stamped before its time 0 (held up on its way, or the watch's thread started late)
     * moves time 0 back to it, with the times of what it holds, so that nothing is too late to judge before the
     * monitor judged anything.
     */
    private long joined(long micros) {
        if (startSeen || judgedTo != Long.MIN_VALUE || micros >= 0) {
            return micros;
        }
        timeline.startedAt(timeline.zeroEpochNanos(), -micros);
        held.forEach(h -> h.micros -= micros); // the same shift for all: their order stays
        clockStart = clockStart == Long.MAX_VALUE ? clockStart : clockStart - micros;
        stopAt = stopAt == Long.MAX_VALUE ? stopAt : stopAt - micros;
        endAt = endAt == Long.MAX_VALUE ? endAt : endAt - micros;
        return 0;
    }

    /**
     * A monitor that joined during a run saw no start: it learns the run's announced end from the tester's answers
     * to its clock pings, so that it lets no time pass beyond that end while the run's stop is on its way (a deadline
     * just after the end, which the tester did not judge, is not an alarm either).
     */
    private void learnAnnouncedEnd() {
        if (startSeen || endAt != Long.MAX_VALUE) {
            return;
        }
        TesterSide.AnnouncedEnd announced = tester.announcedEnd();
        if (announced.endNanos() > 0 && !announced.runId().isEmpty()
                && (runId.isEmpty() || runId.equals(announced.runId()))) {
            runIs(announced.runId());
            endAt = Math.floorDiv(announced.endNanos() - timeline.zeroEpochNanos(), 1000);
        }
    }

    /** An acknowledgement places the input it names where its adapter applied it. */
    private void acknowledged(IDtronChannelValued ack) {
        Held h = inputs.remove(ack.getAckedSender() + "/" + ack.getAckedSequence());
        if (h == null || !held.remove(h)) {
            return;
        }
        // the first acknowledgement counts, as for the tester: one member applies an input
        h.micros = Math.max(h.micros, timeline.eventMicros(ack));
        h.errorMicros = RunTimeline.errorMicros(ack);
        h.awaitingAck = false;
        held.add(h);
    }

    /**
     * The monitor's thread judges, in time order, every held event up to {@code until}, and lets time pass to {@code
     * timeTo} (at most {@code until}).
     */
    private void judge(long until, long timeTo) {
        if (monitor == null) {
            return;
        }
        long to = Math.min(release(until), timeTo);
        if (to >= clockStart && to > judgedTo) {
            String silent = null;
            if (!monitor.allowsTimeTo(to)) {
                // a deadline passed: first what the adapters sent before it, then what this member received and has
                // not handed over yet
                silent = probeAdapters();
                catchUp();
                to = Math.min(to, release(to));
            }
            Alarm a = monitor.advanceTo(to);
            if (a != null && silent != null) {
                sink.note(silent);
            }
            report(a, null, false);
            judgedTo = Math.max(judgedTo, to);
        }
    }

    /**
     * Judges the held events up to {@code to}, in time order, but for a tester's input still waiting for its
     * acknowledgement (which may place it later): returns how far time may pass, {@code to} or that input's time.
     */
    private long release(long to) {
        while (!held.isEmpty() && held.peek().micros <= to && !monitor.stopped()) {
            Held h = held.peek();
            if (h.awaitingAck && System.nanoTime() < h.ackDeadline) {
                return h.micros;
            }
            held.poll();
            inputs.remove(h.message.getSender() + "/" + h.message.getSequence());
            observe(h);
        }
        return to;
    }

    /**
     * Before the monitor lets a deadline pass, it asks the adapters as the tester does ({@link TesterSide#probe}, with
     * a ping every member answers whoever sent it): the members that send the model's outputs (every other member but
     * the testers when none said it sends one). An answer comes after everything its member sent before it, so an
     * output stamped before the deadline whose message was held up is then here. Returns what to say with an alarm
     * about the members that did not answer within {@link #PROBE_TIMEOUT} (stopped, overloaded, or members that do
     * not answer probes: taps, other producers), or null when all answered.
     */
    private String probeAdapters() {
        Set<String> askedFor = new TreeSet<>();
        Set<String> others = new TreeSet<>(dtron.getMembers());
        others.remove(dtron.getMemberId());
        dtron.getTester().ifPresent(others::remove);
        others.removeAll(tester.getOtherTesters());
        tester.getMembersServedChannels().forEach((member, served) -> {
            if (others.contains(member) && served.sends().stream().anyMatch(c -> positions.containsKey(c)
                    && !inputNames.contains(c))) {
                askedFor.add(member);
            }
        });
        Set<String> expected = askedFor.isEmpty() ? others : askedFor;
        if (expected.isEmpty()) {
            return null;
        }
        Set<String> answered;
        try {
            answered = tester.probe(expected, PROBE_TIMEOUT);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return "the monitor was interrupted while it asked the adapters for what they sent before the deadline";
        }
        List<String> silent = expected.stream().filter(m -> !answered.contains(m)).toList();
        if (silent.isEmpty()) {
            return null;
        }
        return "member" + (silent.size() == 1 ? " " : "s ") + String.join(", ", silent) + " did not answer the"
                + " monitor's probe before the deadline was judged (asked for " + PROBE_TIMEOUT.toMillis() + " ms):"
                + " stopped, overloaded, or not answering probes; what it sent before the deadline may be missing";
    }

    /**
     * Waits until this member's listeners have taken what the bus delivered (a second at most), and takes the events
     * and acknowledgements among it, in order, up to the first other arrival (a shield's message, a run's start or
     * stop), which waits until the deadline was judged: it would judge in the middle of this judgement.
     */
    private void catchUp() {
        try {
            if (!tester.awaitListeners(CATCH_UP_TIMEOUT)) {
                LOG.warn("The bus's listeners did not catch up within {} ms", CATCH_UP_TIMEOUT.toMillis());
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        for (Object next = arrivals.peek(); !done && next instanceof Arrival a && (a.kind().equals("event")
                || a.kind().equals(Dtron.ACK.getChannelName())); next = arrivals.peek()) {
            take((Arrival) arrivals.poll());
        }
    }

    private void observe(Held h) {
        if (h.micros < monitor.lastMicros()) {
            late(h); // the monitor moved past it (a re-synchronisation at a deadline)
            return;
        }
        Event e = new Event(h.message.getChannelName(), h.message.getVariables());
        events++;
        judgedTo = Math.max(judgedTo, h.micros);
        report(monitor.observe(e, h.micros, h.errorMicros + settings.toleranceMicros()), h.message, false);
    }

    /** An event older than what the monitor judged: it cannot be placed, so the monitor forgets what it knew. */
    private void late(Held h) {
        late++;
        monitor.forgetHistory();
        sink.note(h.message.getChannelName() + " from " + h.message.getSender() + " came "
                + (Math.max(judgedTo, monitor.lastMicros()) - h.micros)
                + " us after the monitor had judged its time (reorder window " + window.micros() + " us): not judged;"
                + monitor.gaveUp().map(why -> " the monitor stops following the run: " + why)
                        .orElse(" the monitor starts again from every reachable state"));
    }

    /**
     * The shield judges a message of its channel as it arrives: the held events before it first, then it; an
     * allowed message is republished on the shielded channel, a forbidden one withheld.
     */
    private void shield(IDtronChannelValued m) {
        if (monitor == null) {
            withheld++; // before the first run start the shield knows nothing: it passes nothing
            return;
        }
        if (!ofThisRun(m) || stopAt != Long.MAX_VALUE) {
            return;
        }
        if (timeline.eventMicros(m) > endAt) {
            afterEnd++; // after the run's announced end: the tester judges it not, nor does the shield
            return;
        }
        long micros = Math.max(joined(timeline.eventMicros(m)), Math.max(judgedTo, monitor.lastMicros()));
        clockStart = Math.min(clockStart, micros);
        judge(micros, micros);
        events++;
        micros = Math.max(micros, monitor.lastMicros()); // a deadline passed on the way re-synchronised it
        Alarm a = monitor.withhold(new Event(m.getChannelName(), m.getVariables()), micros,
                RunTimeline.errorMicros(m) + settings.toleranceMicros());
        judgedTo = Math.max(judgedTo, micros);
        if (a == null) {
            try {
                // the event time on this member's clock: the producer's, through the run's clock
                dtron.send(shieldedChannel.constructValued(m.getVariables()), Math.max(1, m.getEventTimeNanos()
                        + m.getClockOffsetNanos() - dtron.getClockOffsetNanos()));
            } catch (DtronException | IllegalStateException e) {
                LOG.warn("Cannot republish {}: {}", m, e.getMessage());
            }
            return;
        }
        withheld++;
        report(a, m, true);
    }

    private void widen(IDtronChannelValued m, long eventMicros) {
        long received = Math.floorDiv(m.getReceiveTimeNanos() + dtron.getClockOffsetNanos()
                - timeline.zeroEpochNanos(), 1000);
        window.arrived(Math.max(0, received - eventMicros), received, m.getChannelName() + " from " + m.getSender())
                .ifPresent(w -> sink.note("reorder window widened to " + w + " us: " + m.getChannelName() + " from "
                        + m.getSender() + " took " + (received - eventMicros) + " us"));
    }

    private void report(Alarm a, IDtronChannelValued message, boolean withholding) {
        if (a == null) {
            return;
        }
        violations = monitor.violations();
        sink.alarm(a, withholding);
        publish(a.busValues().get("number"), a.reason().code(), a.event() == null ? 0
                : positions.getOrDefault(a.event().channel(), 0), message == null ? 0 : message.getSequence(),
                withholding, false, a.micros());
    }

    private void publishVerdict() {
        long at = judgedTo == Long.MIN_VALUE ? 0 : judgedTo;
        publish(violations, monitor == null || monitor.firstAlarm() == null ? 0
                : monitor.firstAlarm().reason().code(), 0, 0, false, true, at);
    }

    private void publish(int number, int reason, int channel, long sequence, boolean withholding, boolean verdict,
            long micros) {
        Map<String, Integer> values = new LinkedHashMap<>();
        values.put("number", number);
        values.put("reason", reason);
        values.put("channel", channel);
        values.put("sequence", (int) Math.min(Integer.MAX_VALUE, sequence));
        values.put("withheld", withholding ? 1 : 0);
        values.put("verdict", verdict ? 1 : 0);
        // the alarm's time on this member's wall clock, which the message's clock offset brings to the run's
        long epochNanos = timeline.epochNanos(micros) - dtron.getClockOffsetNanos();
        try {
            dtron.send(Dtron.ALARM.constructValued(values), Math.max(1, epochNanos));
        } catch (DtronException | IllegalStateException e) {
            LOG.warn("Cannot publish the {} on {}: {}", verdict ? "verdict" : "alarm", Dtron.ALARM.getChannelName(),
                    e.getMessage());
        }
    }
}
