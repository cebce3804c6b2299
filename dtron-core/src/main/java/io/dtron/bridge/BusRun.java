package io.dtron.bridge;

import io.dtron.api.ClockOffset;
import io.dtron.api.Dtron;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.DtronStats;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.ServedChannels;
import io.dtron.api.internal.TesterSide;
import io.dtron.bridge.internal.AdapterProbes;
import io.dtron.bridge.internal.ChannelOwners;
import io.dtron.bridge.internal.InputDelays;
import io.dtron.bridge.internal.LatencyRecorder;
import io.dtron.bridge.internal.ReorderWindow;
import io.dtron.bridge.internal.RunMembers;
import io.dtron.bridge.internal.RunTesters;
import io.dtron.bridge.internal.RunTimeline;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.model.TestInterface;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Collections;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.Set;
import java.util.TreeMap;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ThreadLocalRandom;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * One run on a DTRON bus, as one owner keeps it: the handshake with the adapters and the other testers, the run id,
 * time 0, the members' clock offsets, the events' times on the run's clock, the reorder window, the delays, the
 * membership and the end of the run. The engine side is role-specific and given at {@link #start}: the tester's is
 * a {@link BusBridge}, the engine's {@link io.dtron.engine.Adapter}; the run hands it every event with its time on the
 * run's clock, in the bus's order, through the engine's {@link AdapterContext}.
 *
 * <p>The run is a bus member that declares the channels of the model's interface (channel and variable names
 * as in the interface), so that a message on any other channel, or with unknown or missing variables, or that is
 * no valid {@code Sync}, is rejected, logged and counted in {@link #stats()}. When the run starts it publishes
 * {@link Dtron#RUN_START} with the run's time unit, and when it ends {@link Dtron#RUN_STOP}. Every input the engine
 * applies is published on the input's channel ({@link #publishInput}); every message another member publishes on an
 * output channel is reported to the engine as it arrives. Its own inputs come back in the bus's total order and are
 * not outputs. It is the bus's {@linkplain DtronOptions.Builder#tester tester}: adapters estimate their clock's
 * offset to its clock, and its runs carry a run id, so messages of another run on the same bus are ignored ({@link
 * #messagesOfOtherRuns()}). An output is reported with its event time (when its sender says the system produced it,
 * corrected by the sender's clock offset, on the run's clock since time 0), not the time it arrived, and an input is
 * placed where its adapter's {@linkplain Dtron#ACK acknowledgement} says it was applied; so a message that crossed
 * another on the bus is judged in its true place (within the run's reorder window, see {@link
 * io.dtron.engine.TestOptions#reorderWindowMicros()}). For every message received, t1 (its publish time) and t2 (its
 * receive time) are recorded: {@link #outputLatency()} and {@link #inputLatency()} summarise t2 - t1.
 *
 * <p>When a member other than this one that served the run when it started leaves during the run (it closed,
 * or its process died and failure detection noticed), the run ends INCONCLUSIVE naming the member: the run
 * cannot know which parts of the system under test that member stood for, so it assumes the model may be waiting on
 * it. A member serves the run when it said in the handshake that it receives an input or sends an output of the
 * model, or said nothing (it may serve anything). A member that joined during the run, or that serves no channel
 * of the model (an observer, a tester refused because of this run), never served it, and may leave.
 *
 * <p>Each output has one owner: the member that said it sends it. When two members say so, or a member sends on it
 * without having said so, the run names them: before a run in {@link #ownersConflict()}, at its start and at the
 * next message on that output during it, which ends the run INCONCLUSIVE rather than judge their messages as one
 * system's. Members whose messages carry another run's id own nothing of this one.
 */
public final class BusRun implements AutoCloseable {
    private static final Logger LOG = LoggerFactory.getLogger(BusRun.class);
    /** How long {@link #stop()} waits for its own end-of-run message to come back from the bus. */
    static final Duration STOP_ECHO_TIMEOUT = Duration.ofSeconds(2);
    /** How long an adapter member gets to answer the tester's probe before a missed deadline (see unreachable). */
    static final Duration PROBE_TIMEOUT = AdapterProbes.PROBE_TIMEOUT;
    /** How long the tester that started a run of several testers waits for the others' verdicts before it ends it. */
    static final Duration VERDICTS_TIMEOUT = Duration.ofSeconds(30);
    /** How far ahead a run of several testers is started, so that every tester starts its engine at time 0. */
    static final Duration RUN_LEAD = Duration.ofMillis(500);
    /**
     * The probes before a run ({@link #warmUp}) come one after the other: a thousand rounds and more, so that the JIT
     * compiler of a fresh JVM compiles the path of an input, here and in the adapters, before time 0.
     */
    static final Duration WARM_UP_SPACING = Duration.ZERO;
    /** How long the probes before a run last at least while the engine warms up meanwhile. */
    static final Duration WARM_UP_MINIMUM = Duration.ofMillis(400);
    /** How long the probes before a run last at most, steady or not. */
    static final Duration WARM_UP_LIMIT = Duration.ofSeconds(3);
    /**
     * How long a run's start waits for the listeners' thread to catch up with what the bus told this member (who
     * serves what), so that it decides which members serve the run on one view (see {@link #startRun}).
     */
    static final Duration CATCH_UP_TIMEOUT = Duration.ofSeconds(2);
    /** The smallest automatic reorder window, in microseconds (see {@link Delays#autoWindowMicros()}). */
    public static final long AUTO_WINDOW_FLOOR_MICROS = ReorderWindow.AUTO_FLOOR_MICROS;
    /** How many times the longest delay measured before a run the automatic reorder window allows for. */
    public static final int AUTO_WINDOW_DELAY_FACTOR = ReorderWindow.DELAY_FACTOR;

    private final Dtron dtron;
    /** What only a tester does with its bus member. */
    private final TesterSide tester;
    /** Whether this run takes part in a run another tester starts ({@link #join}). */
    private final boolean joining;
    private final Map<String, IDtronChannel> inputs;
    private final Set<String> outputs;
    private final LatencyRecorder outputLatency = new LatencyRecorder();
    private final LatencyRecorder inputLatency = new LatencyRecorder();
    private final Set<String> watched = ConcurrentHashMap.newKeySet();
    /** The members whose messages carried another run's id: they serve that run, not this run's. */
    private final Set<String> otherRunMembers = ConcurrentHashMap.newKeySet();
    /** The members on the bus when the run started. */
    private volatile Set<String> startMembers = Set.of();
    /** Who owns the outputs (see {@link ChannelOwners}). */
    private final ChannelOwners owners;
    /** What the other members serve, in the bus's order with their messages (the listeners' thread keeps it). */
    private volatile Map<String, ServedChannels> served;
    /** Who is on the bus for the run: what the members serve, the testers of other runs, the awaited adapters. */
    private final RunMembers runMembers;
    private final AtomicBoolean warnedBeforeStart = new AtomicBoolean();
    private final AtomicLong outputsAfterEnd = new AtomicLong();
    private volatile CountDownLatch ownStop = new CountDownLatch(1);
    private final AtomicLong otherRuns = new AtomicLong();
    /** The latest clock offset estimate each adapter member sent, by member. */
    private final Map<String, ClockOffset> offsets = new ConcurrentHashMap<>();
    /** The number of each input of the run (1 for the first) by the sequence number of its message. */
    private final Map<Long, Long> inputNumbers = new HashMap<>();
    /** Each input of the run published and not yet acknowledged, by its number. */
    private final Map<Long, SentInput> sentInputs = new ConcurrentHashMap<>();
    private long performed;
    /** The delays of this run's messages by "input NAME" and "output NAME" (see {@link ChannelDelay}). */
    private final Map<String, ChannelDelay> runDelays = new ConcurrentHashMap<>();
    /** How long inputs take to reach the adapters, for {@link #inputDelayMicros}. */
    private final InputDelays inputDelays = new InputDelays();
    /** The probes of the adapter members before a run, which measure how long inputs take to reach them. */
    private final AdapterProbes probes;
    /** Whether {@link #prepare} got the next run ready, which its start then takes as it is. */
    private boolean prepared;
    /** Inputs of other testers of the run, observed as outputs, until their acknowledgements say when they happened. */
    private final Map<String, IDtronChannelValued> heldPeerInputs = new ConcurrentHashMap<>();
    /** The testers of a run of several: ready to join, joined, the leader, their verdicts. */
    private final RunTesters runTesters;
    /** Time 0 of the run and the times of its messages on the run's clock. */
    private final RunTimeline timeline;
    /** The run's reorder window (Delta), fixed or automatic. */
    private final ReorderWindow window = new ReorderWindow();
    /** Whether the adapters of the current run acknowledge inputs (see {@link #acknowledgesInputs()}). */
    private volatile boolean acknowledging;
    private volatile AdapterContext context;
    private volatile boolean running;
    private volatile String runId = "";

    private BusRun(Dtron dtron, Map<String, IDtronChannel> channels, TestInterface testInterface,
            boolean joining) {
        this.dtron = dtron;
        this.tester = TesterSide.of(dtron);
        this.joining = joining;
        this.timeline = new RunTimeline(dtron::currentTimeNanos);
        this.runTesters = new RunTesters(dtron, tester, joining);
        this.probes = new AdapterProbes(dtron, tester, inputDelays, this::testersOfOtherRuns, this::isPeerTester);
        Map<String, IDtronChannel> inputChannels = new LinkedHashMap<>();
        testInterface.inputs().forEach(c -> inputChannels.put(c.name(), channels.get(c.name())));
        this.inputs = Map.copyOf(inputChannels);
        this.outputs = Set.copyOf(testInterface.outputs().stream().map(TestInterface.ObservableChannel::name).toList());
        this.owners = new ChannelOwners(inputs.keySet(), outputs);
        this.runMembers = new RunMembers(dtron, tester, inputs.keySet(), outputs, joining);
        tester.addServedChannelsListener(this::servedChanged);
        this.served = tester.getMembersServedChannels();
        for (IDtronChannel channel : channels.values()) {
            dtron.addDtronListener(new DtronListener(channel) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    received(message);
                }

                @Override
                protected boolean autoAcknowledge() {
                    return false; // a tester observes; the adapters apply inputs
                }
            });
        }
        // the tester publishes its inputs: in a run of several testers, they are other testers' outputs
        dtron.declareOutputs(inputs.values());
        dtron.addDtronListener(new DtronListener(Dtron.RUN_VERDICT) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                peerVerdict(message);
            }
        });
        dtron.addDtronListener(new DtronListener(Dtron.RUN_START) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                runTesters.started(message);
            }
        });
        dtron.addDtronListener(new DtronListener(Dtron.ACK) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                acknowledged(message);
            }
        });
        dtron.addDtronListener(new DtronListener(Dtron.RUN_STOP) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                if (message.getSender().equals(dtron.getMemberId())) {
                    ownStop.countDown();
                } else if (joining && running && !ofOtherRun(message)) {
                    context.inconclusive("tester " + message.getSender() + ", which started the run, ended it");
                }
            }
        });
        dtron.addMembershipListener(this::membershipChanged);
    }

    /**
     * Joins the bus as the tester of a model, which starts its runs.
     *
     * @param testInterface the model's interface: its channels are declared on {@code options}
     * @param options       how to join the bus
     * @throws IllegalArgumentException if a channel name of the interface cannot be a bus channel (a channel array
     *                                  element, the reserved names of {@link Dtron#RUN_START} and {@link
     *                                  Dtron#RUN_STOP}), or an input and an
     *                                  output have the same name and different variables
     * @throws DtronException           if the bus cannot be joined
     */
    public static BusRun connect(TestInterface testInterface, DtronOptions.Builder options) {
        return connect(testInterface, options, false);
    }

    /**
     * Joins the bus as one tester of a run that another tester starts ({@code dtron run --join}): it judges its own
     * model's channels, on the starting tester's clock, from that tester's run start on. Call {@link #readyToJoin()}
     * when its channels are served, then {@link #awaitRun}.
     *
     * @throws IllegalArgumentException as {@link #connect} does
     * @throws DtronException           if the bus cannot be joined
     */
    public static BusRun join(TestInterface testInterface, DtronOptions.Builder options) {
        return connect(testInterface, options, true);
    }

    private static BusRun connect(TestInterface testInterface, DtronOptions.Builder options, boolean joining) {
        Map<String, IDtronChannel> channels = channels(testInterface);
        List<IDtronChannel> declared = new ArrayList<>(channels.values());
        declared.add(Dtron.RUN_START);
        declared.add(Dtron.RUN_STOP);
        declared.add(Dtron.RUN_VERDICT);
        Dtron dtron = Dtron.connect(options.channels(declared).tester(!joining).build());
        try {
            return new BusRun(dtron, channels, testInterface, joining);
        } catch (RuntimeException e) {
            dtron.close();
            throw e;
        }
    }

    /** Returns whether this run joins a run another tester starts. */
    public boolean isJoining() {
        return joining;
    }

    /**
     * A joining tester tells the bus it is ready, once it knows its clock's offset to the tester that starts the
     * run (the run's clock): that tester waits for it.
     *
     * @return whether it was ready before the timeout (it knew a tester and its clock offset)
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean readyToJoin(Duration timeout) throws InterruptedException {
        return runTesters.readyToJoin(timeout);
    }

    /** Returns the members that said they are testers ready to join the next run this run starts. */
    public List<String> joiningTesters() {
        return runTesters.ready();
    }

    /**
     * Waits until at least {@code count} testers said they are ready to join the next run this member starts.
     *
     * @return whether they did, before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean awaitJoiningTesters(int count, Duration timeout) throws InterruptedException {
        return runTesters.awaitReady(count, timeout);
    }

    /**
     * Starts a run of several testers: publishes the run start with time 0 {@link #RUN_LEAD} from now, so that
     * every tester of the run (this one and those that {@linkplain #joiningTesters() joined}) can start its engine at
     * that time. The next {@link #start} does not publish it again.
     *
     * @param timeUnitMicros the run's time unit, which the start carries
     * @return time 0 of the run on this member's wall clock, in nanoseconds since the epoch
     * @throws DtronException if the bus did not take the message
     */
    public long announceRun(long timeUnitMicros) {
        runTesters.announce();
        runId = Long.toHexString(ThreadLocalRandom.current().nextLong() >>> 16);
        tester.setRunId(runId);
        long zero = dtron.currentTimeNanos() + RUN_LEAD.toNanos();
        dtron.send(Dtron.RUN_START.constructValued(Map.of("timeunit", (int) Math.min(Integer.MAX_VALUE,
                timeUnitMicros))), zero);
        timeline.announce(zero);
        return zero;
    }

    /**
     * On a joining tester: waits for the run start of the tester that starts the run.
     *
     * @return time 0 of the run on this member's wall clock, in nanoseconds since the epoch; -1 if no run started
     *         before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public long awaitRun(Duration timeout) throws InterruptedException {
        IDtronChannelValued start = runTesters.awaitStart(timeout);
        if (start == null) {
            return -1;
        }
        runId = start.getRunId();
        long zero = RunTimeline.zeroOf(start, dtron.getClockOffsetNanos());
        timeline.announce(zero);
        return zero;
    }

    /**
     * After the verdict of a run of several testers: tells the other testers this one's verdict; the tester that
     * started the run then waits (at most {@link #VERDICTS_TIMEOUT}) until every tester that joined told its
     * verdict or left, and ends the run with {@link Dtron#RUN_STOP}. Does nothing on a run of one tester, which
     * {@link #stop()} ended.
     */
    public void finish(int verdictExitCode) {
        if (!runTesters.several()) {
            return;
        }
        runTesters.tell(verdictExitCode);
        if (joining) {
            return;
        }
        runTesters.awaitVerdicts(VERDICTS_TIMEOUT);
        publishStop(0);
    }

    /**
     * In a run of several testers: time 0 as {@link #announceRun} or {@link #awaitRun} set it, so that the engine
     * of every tester counts from the same instant; empty otherwise.
     */
    public java.util.OptionalLong timeZero() {
        return timeline.timeZero();
    }

    /**
     * Hands every later message on the bus to {@code listener}, in the bus's order, for a trace of the whole bus
     * (see {@link Dtron#addRecordListener}); {@link #removeRecordListener} stops it.
     */
    public void addRecordListener(java.util.function.Consumer<io.dtron.api.BusRecord> listener) {
        dtron.addRecordListener(listener);
    }

    /** Stops handing messages to a listener of {@link #addRecordListener}. */
    public void removeRecordListener(java.util.function.Consumer<io.dtron.api.BusRecord> listener) {
        dtron.removeRecordListener(listener);
    }

    /**
     * Whether the adapters acknowledge the inputs they apply: every input channel is received by a member that took
     * part in the channel-serving handshake, as every member built on DTRON's API does (and acknowledges inputs
     * when its listeners return). Adapters waited for by number ({@code --wait-for-adapters N}) may not.
     */
    public boolean acknowledgesInputs() {
        return acknowledging;
    }

    /** Whether every input channel is received by a member of the handshake that is no tester of this run. */
    private boolean inputsReceivedByHandshakeMembers() {
        Set<String> received = new java.util.HashSet<>();
        tester.getMembersServedChannels().values().stream().filter(s -> !isPeerTester(s.member()))
                .forEach(s -> received.addAll(s.receives()));
        return !inputs.isEmpty() && received.containsAll(inputs.keySet());
    }

    /** Returns the verdicts the other testers of the run told, as exit codes by member. */
    public Map<String, Integer> peerVerdicts() {
        return runTesters.verdicts();
    }

    /** Another tester of the run told its verdict: one other than PASSED ends this run too. */
    private void peerVerdict(IDtronChannelValued message) {
        if (message.getSender().equals(dtron.getMemberId()) || ofOtherRun(message)) {
            return;
        }
        int verdict = runTesters.told(message);
        watched.remove(message.getSender()); // it may leave now
        if (running && verdict != 0) {
            context.inconclusive("tester " + message.getSender() + " of this run ended it " + (verdict == 2
                    ? "FAILED" : "INCONCLUSIVE") + " (its own verdict says why)");
        }
    }

    /** The bus channel of every input and output of the interface, by name. */
    private static Map<String, IDtronChannel> channels(TestInterface testInterface) {
        Map<String, IDtronChannel> channels = new LinkedHashMap<>();
        List<TestInterface.ObservableChannel> all = new ArrayList<>(testInterface.inputs());
        all.addAll(testInterface.outputs());
        for (TestInterface.ObservableChannel c : all) {
            if (Dtron.isReservedChannel(c.name())) {
                throw new IllegalArgumentException("channel '" + c.name() + "' of the model's interface has a name"
                        + " DTRON reserves for announcing the start and end of a run; rename it");
            }
            IDtronChannel channel;
            try {
                channel = IDtronChannel.of(c.name(), c.variables().stream().map(TestInterface.AttachedVariable::name)
                        .toList());
            } catch (IllegalArgumentException e) {
                throw new IllegalArgumentException("channel '" + c.name() + "' of the model's interface cannot travel"
                        + " on the bus: " + e.getMessage());
            }
            IDtronChannel other = channels.putIfAbsent(c.name(), channel);
            if (other != null && !other.equals(channel)) {
                throw new IllegalArgumentException("input and output '" + c.name() + "' carry different variables ("
                        + other.getVariableNames() + ", " + channel.getVariableNames() + "), so the bus cannot"
                        + " carry both on one channel");
            }
        }
        return channels;
    }

    /**
     * Returns the bus member this run speaks through, for DTRON's channels beside the run's own: a controller's model
     * versions ({@link io.dtron.api.Dtron#MODEL_VERSION}).
     */
    public Dtron member() {
        return dtron;
    }

    /** Returns this member's id on the bus. */
    public String memberId() {
        return dtron.getMemberId();
    }

    /** Returns the members on the bus now, oldest first, this run included. */
    public List<String> members() {
        return dtron.getMembers();
    }

    /**
     * Waits until at least {@code count} members other than this run and other testers are on the bus.
     *
     * @return whether they were, before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean awaitAdapters(int count, Duration timeout) throws InterruptedException {
        return runMembers.awaitAdapters(count, timeout);
    }

    /**
     * Returns the channels of the model that no adapter on the bus serves yet, as the handshake tells (see {@link
     * TesterSide#getMembersServedChannels()}): "input NAME" for an input no member listens to, "output NAME" for an
     * output no member declared or sent; empty when every channel is served. Testers of other runs do not count.
     */
    public List<String> unservedChannels() {
        return runMembers.unservedChannels();
    }

    /**
     * Waits until every channel of the model is served by an adapter on the bus (see {@link #unservedChannels()}).
     *
     * @return whether it was, before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean awaitChannelsServed(Duration timeout) throws InterruptedException {
        return runMembers.awaitChannelsServed(timeout);
    }

    /** Returns what each adapter member on the bus said it serves, by member id (testers left out). */
    public Map<String, ServedChannels> servedChannels() {
        return runMembers.servedChannels();
    }

    /**
     * The testers on the bus whose runs are not this run's: every other tester that greeted the bus, but, for a
     * joining tester, the one whose run it joins.
     */
    private Set<String> testersOfOtherRuns() {
        return runMembers.testersOfOtherRuns();
    }

    /**
     * The delays measured on the bus before a run: the longest time a message of an adapter member took to reach the
     * tester (publish to receipt, corrected by the member's clock offset), and the largest error bound of the
     * offsets involved.
     *
     * @param maxDelayNanos the longest delay seen, in nanoseconds
     * @param maxErrorNanos the largest clock offset error bound, in nanoseconds
     * @param messages      how many messages were measured
     * @param members       how many adapter members sent them
     */
    public record Delays(long maxDelayNanos, long maxErrorNanos, long messages, int members) {
        /**
         * The automatic reorder window for these delays: {@value #AUTO_WINDOW_DELAY_FACTOR} times the longest delay
         * plus twice the clocks' error bound, rounded up to a millisecond, and at least {@link
         * #AUTO_WINDOW_FLOOR_MICROS}, in microseconds.
         */
        public long autoWindowMicros() {
            return ReorderWindow.auto(maxDelayNanos, maxErrorNanos);
        }
    }

    /**
     * Measures the delays of the adapters' messages before a run: asks every adapter member {@code rounds} times,
     * {@code spacing} apart, to answer (see {@link TesterSide#probe}), and sums up every message of theirs measured so far
     * (their pings since they joined included), so that the first, slow messages of a fresh process count too. A
     * member that joined just now is given two seconds to send its first clock offset estimate,
     * without which its delays cannot be measured.
     *
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public Delays measureDelays(int rounds, Duration spacing) throws InterruptedException {
        return probes.measure(rounds, spacing);
    }

    /**
     * Before time 0: probes the adapters until their round trips are steady ({@link #probeUntilSteady}), round after
     * round without a pause, at most {@link #WARM_UP_LIMIT}, and at least {@link #WARM_UP_MINIMUM} when the engine
     * warms up meanwhile ({@code engineWarmsUp}).
     *
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public Probing warmUp(boolean engineWarmsUp) throws InterruptedException {
        return probeUntilSteady(WARM_UP_SPACING, engineWarmsUp ? WARM_UP_MINIMUM : Duration.ZERO, WARM_UP_LIMIT);
    }

    /**
     * The delays measured before a run without probing again ({@link #measureDelays} with no round): what the
     * probes of {@link #warmUp} measured, and for a joining tester what passes by, the others' pings and answers.
     *
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public Delays measuredDelays() throws InterruptedException {
        return measureDelays(0, Duration.ZERO);
    }

    /**
     * The probes before a run ({@link #probeUntilSteady}).
     *
     * @param rounds     how many rounds were probed
     * @param steady     whether the round trips of the last rounds were steady (else the time limit ended them)
     * @param lastMicros the longest round trip of the last {@value InputDelays#STEADY_ROUNDS} rounds, in microseconds
     * @param millis     how long the probing took, in milliseconds
     */
    public record Probing(int rounds, boolean steady, long lastMicros, long millis) {
    }

    /**
     * Probes every adapter member in rounds, {@code spacing} apart (zero: one after the other), for at least {@code
     * minimum} (while this process warms up, say) and until the round trips of the last rounds are steady ({@link
     * InputDelays#steady}) and no longer get faster ({@link InputDelays#noLongerImproving}), or {@code limit} has
     * passed: a fresh JVM's first compilations and collections, here and in the adapters, then
     * happen before the run, not in it. Each probe takes the way of an input ({@link TesterSide#probeAsInput}): through
     * the adapter's listeners' thread and its acknowledgement, without reaching a listener, so that the adapter's
     * first input of the run does not take that way for the first time. Each member's longest round trip in the last
     * rounds is taken as the delay of the inputs it receives until the run's acknowledgements say more ({@link
     * #inputDelayMicros}). Nothing to probe (no adapter member) returns at once.
     *
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public Probing probeUntilSteady(Duration spacing, Duration minimum, Duration limit) throws InterruptedException {
        return probes.untilSteady(spacing, minimum, limit);
    }

    /**
     * How long an input on {@code channel} may take to reach the system: the longer of the probe round trip before
     * the run of the adapters that receive it and the 99th percentile of the delays of its inputs acknowledged so far
     * (published to applied), each with its clock error; 0 before anything was measured.
     */
    public long inputDelayMicros(String channel) {
        return probes.inputDelayMicros(channel);
    }

    /**
     * How far ahead of its time an input on {@code channel} is published ({@link #publishInput(Event, long)}): when
     * every adapter that receives it holds inputs until they are due (every member of DTRON's Java API does), the
     * way such an input takes, measured as for {@link #inputDelayMicros} of inputs sent at their time, which then
     * says only how late after its due time one was applied; 0 when some receiver applies inputs on arrival (the
     * Python and C clients, TRON's adapters behind a bridge).
     */
    public long inputLeadMicros(String channel) {
        return probes.inputLeadMicros(channel);
    }

    /**
     * Sets the reorder window the next run starts with, in microseconds, and whether the run widens it when a
     * message of the run takes more than half of it (to twice that message's delay, rounded up to a millisecond):
     * {@code --delta auto}. A fixed window ({@code auto} false) stays as the user set it.
     */
    public void reorderWindow(long micros, boolean auto) {
        window.set(micros, auto);
    }

    /**
     * Sets the reorder window the next run starts with: {@code fixedMicros} ({@code --delta US}), or when empty the
     * automatic one for the delays measured before the run ({@link Delays#autoWindowMicros()}), widened during the
     * run (see {@link #reorderWindow(long, boolean)}).
     *
     * @return the window the run starts with, in microseconds
     */
    public long reorderWindow(Delays measured, java.util.OptionalLong fixedMicros) {
        reorderWindow(fixedMicros.orElse(measured.autoWindowMicros()), fixedMicros.isEmpty());
        return window.micros();
    }

    /** Returns the reorder window now: as set, or as widened during the run. */
    public long reorderWindowMicros() {
        return window.micros();
    }

    /** Whether the reorder window is automatic: widened during the run when a message takes more than half of it. */
    public boolean reorderWindowAutomatic() {
        return window.automatic();
    }

    /**
     * Returns how the window was widened during the last run, one line each ("to 12.0 ms at t=3.2 s: output tick
     * took 5.9 ms"); empty if it was not.
     */
    public List<String> widenings() {
        return window.widenings();
    }

    /**
     * Returns the delays of each channel's messages in the last run, inputs (published to applied, from the inputs
     * an adapter acknowledged) and outputs (produced to received), by direction and name.
     */
    public List<ChannelDelay> runDelays() {
        return new TreeMap<>(runDelays).values().stream().toList();
    }

    /**
     * Remembers the adapters on the bus now (the members other than this run and other testers), once the
     * tester has waited for them: when one has left by the start of the next run, that run ends INCONCLUSIVE at once,
     * naming it, as when one leaves during the run (else the run would go on without it and fail when its first
     * output does not come). When every channel of the model is served now by what the adapters said in the
     * handshake, the handshake decides instead: the run ends so only if a channel is no longer served at its start
     * (a member that left without serving one, such as a tester refused because of this run, changes nothing).
     */
    public void expectAdapters() {
        runMembers.expectAdapters();
    }

    /**
     * Starts the run, with time 0 at the engine's clock's now (or, in a run of several testers, as {@link
     * #announceRun} or {@link #awaitRun} set it): publishes the start, unless it was announced, and from now on hands
     * {@code runContext} the run's events with their times on the run's clock.
     */
    public void start(AdapterContext runContext) {
        startRun(runContext);
        // what the tester checked before the start may have changed since: a member that joined in between
        ownersConflict().ifPresent(conflict -> context.inconclusive(conflict));
        // the awaited adapters that were no longer members at the start (those that leave later are watched)
        runMembers.goneBeforeStart(startMembers).ifPresent(context::inconclusive);
    }

    /**
     * Gets the next run ready before its time 0: clears what the last run left and takes the view of the members
     * and what they serve that the run decides by, once the bus's listeners have caught up (a round trip through
     * their thread, milliseconds that would otherwise be the run's first). {@link #start} does it when it was not
     * done.
     */
    public void prepare() {
        prepared = true;
        runDelays.clear();
        acknowledging = inputsReceivedByHandshakeMembers();
        heldPeerInputs.clear();
        window.newRun();
        runTesters.runStarts();
        owners.newRun();
        // the members and what they serve, on one view: the announcements of the members on the bus now that the
        // bus has delivered reach the listeners' thread (which keeps served, in order with the members' messages)
        // before the run decides by them; else a member that serves nothing of the model, whose announcement was
        // still queued there, would count as one that said nothing, and its leaving would end the run
        startMembers = Set.copyOf(dtron.getMembers());
        try {
            if (!tester.awaitListeners(CATCH_UP_TIMEOUT)) {
                LOG.warn("The bus's listeners did not catch up within {} ms; the run starts with what they know",
                        CATCH_UP_TIMEOUT.toMillis());
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        Map<String, ServedChannels> servedNow = served;
        // a member that said it serves no channel of the model (an observer) never serves the run, and may leave;
        // one that said nothing may serve anything
        startMembers.stream().filter(m -> !servedNow.containsKey(m) || owners.servesTheModel(servedNow.get(m)))
                .forEach(watched::add);
        watched.remove(dtron.getMemberId());
        watched.removeAll(testersOfOtherRuns()); // refused by this run, they leave

        synchronized (inputNumbers) {
            inputNumbers.clear();
            sentInputs.clear();
            performed = 0;
        }
    }

    private void startRun(AdapterContext runContext) {
        context = Objects.requireNonNull(runContext, "runContext");
        if (!prepared) {
            prepare();
        }
        prepared = false;
        // the run's clock is the starting tester's: a joining tester's own time 0 is its engine's, on that clock
        long nowNanos = dtron.currentTimeNanos() + (joining ? dtron.getClockOffsetNanos() : 0);
        long zeroEpochNanos = timeline.startedAt(nowNanos, runContext.clock().nowMicros());
        if (timeline.takeAnnounced()) {
            running = true;
            return; // a run of several testers: its start was published before the engines started
        }
        runTesters.alone();
        runId = Long.toHexString(ThreadLocalRandom.current().nextLong() >>> 16);
        tester.setRunId(runId);
        // a time unit beyond int range (35 minutes) does not occur in practice; the message carries an int
        int unit = (int) Math.min(Integer.MAX_VALUE, runContext.timeUnitMicros());
        // the adapters' time 0 is the start's event time: the engine's time 0, however late the start is published
        running = true;
        // the run's end, announced so that a monitor judges no further until the stop says where the tester stopped
        long end = runContext.endMicros();
        long endEpochNanos = end == Long.MAX_VALUE ? 0 : timeline.epochNanos(end);
        try {
            tester.sendRunStart(Dtron.RUN_START.constructValued(Map.of("timeunit", unit)), zeroEpochNanos,
                    endEpochNanos);
        } catch (DtronException | IllegalStateException e) {
            LOG.warn("Cannot publish the start of the run: {}", e.getMessage());
            context.inconclusive("cannot publish the start of the run on the bus: " + e.getMessage());
        }
    }

    /**
     * Returns what makes the owners of the model's outputs ambiguous on the bus now, in one line naming the members
     * (see {@link ChannelOwners#conflict}): two members with one id, or an output that two members say they send
     * (the testers of other runs left out). A tester refuses to start a run then; empty when every output has at most
     * one owner.
     */
    public Optional<String> ownersConflict() {
        return owners.conflict(dtron.getMembers(), tester.getMembersServedChannels(), notOwners());
    }

    /**
     * The members that own no channel of this run: this run, the testers of other runs and the members whose
     * messages carried another run's id; during a run also the testers that joined the bus after it started (ready
     * for the next run, they take no part in this one).
     */
    private Set<String> notOwners() {
        Set<String> none = testersOfOtherRuns();
        none.add(dtron.getMemberId());
        none.addAll(otherRunMembers);
        if (running) {
            Set<String> atStart = startMembers;
            served.values().stream().filter(s -> (s.joinsRun() || s.tester()) && !atStart.contains(s.member()))
                    .forEach(s -> none.add(s.member()));
        }
        return none;
    }

    /**
     * Called on the bus's listener thread, in the bus's order, when what the other members serve changed: the
     * outputs that come after it are judged by it (see {@link #received}).
     */
    private void servedChanged(Map<String, ServedChannels> now) {
        served = now;
    }

    /**
     * Returns the other testers on this bus: members that announced themselves as testers (see {@link
     * TesterSide#getOtherTesters()}). A run on a bus with another tester would share its adapters with another run.
     */
    public Set<String> otherTesters() {
        return tester.getOtherTesters();
    }

    /**
     * Returns the testers of other runs (see {@link #otherTesters()}) that joined the bus before this run, once
     * every other member has told whether it is a tester: it answered this tester's greeting in the
     * channel-serving handshake (a tester says that it is one), or greeted the bus as a tester. Members that never
     * tell (adapters built against an API without the handshake) are waited for, three seconds at most. Of two
     * testers that meet on one bus, the one that joined first starts its run and the other, finding it here, does not:
     * the members' order on the bus is the same for all of them.
     *
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public List<String> testersThatJoinedFirst() throws InterruptedException {
        return runMembers.testersThatJoinedFirst();
    }

    /** Returns the id of the current (or last) run, which its messages carry; "" before the first. */
    public String runId() {
        return runId;
    }

    /**
     * Publishes an input of the model on its channel; the engine numbers the inputs it performed from 1, and the
     * adapter's acknowledgement of this one is reported as that number ({@link AdapterContext#inputApplied}).
     *
     * @throws IllegalArgumentException if the event is not an input of the interface
     */
    public void publishInput(Event input) {
        publishInput(input, -1);
    }

    /**
     * Publishes an input of the model ahead of its time, due at {@code dueMicros} on the run's clock: the adapters
     * that receive it hold it until then ({@link #inputLeadMicros}); a negative time publishes it as {@link
     * #publishInput(Event)} does.
     *
     * @throws IllegalArgumentException if the event is not an input of the interface
     */
    public void publishInput(Event input, long dueMicros) {
        IDtronChannel channel = inputs.get(input.channel());
        if (channel == null) {
            throw new IllegalArgumentException("'" + input.channel() + "' is not an input of the interface");
        }
        // the lock holds an acknowledgement that comes back before its input's number is known
        synchronized (inputNumbers) {
            IDtronChannelValued value = channel.constructValued(input.values());
            IDtronChannelValued sent = dueMicros < 0 ? publish(value, "input " + input)
                    : publishAhead(value, timeline.epochNanos(dueMicros), "input " + input);
            performed++;
            if (sent != null) {
                inputNumbers.put(sent.getSequence(), performed);
                sentInputs.put(performed, new SentInput(input.channel(), timeline.publishedMicros(sent), dueMicros));
            }
        }
    }

    /**
     * Publishes {@link Dtron#RUN_STOP} and waits (at most two seconds) until it comes back, so that
     * the latency summaries and {@link #stats()} count every message the bus ordered before the end of the run. In a
     * run of several testers the run goes on until {@link #finish}.
     */
    public void stop() {
        running = false;
        if (!runTesters.several()) {
            publishStop(0);
        }
    }

    /**
     * Ends the run as {@link #stop()} does, with the end of the tester's observation as the stop's event time: the
     * time on the run's clock up to which it judged the events ({@link io.dtron.engine.Adapter#stop(long)}), so that
     * a monitor judges up to the same instant. In a run of several testers, whose stop comes after every tester's
     * verdict ({@link #finish}), the stop is stamped when it is published.
     */
    public void stop(long observedUntilMicros) {
        running = false;
        if (!runTesters.several()) {
            publishStop(timeline.epochNanos(Math.max(0, observedUntilMicros)));
        }
    }

    /**
     * Publishes the end of the run, with {@code eventTimeNanos} as its event time (0: when it is published), and
     * waits for it to come back.
     */
    private void publishStop(long eventTimeNanos) {
        CountDownLatch echo = new CountDownLatch(1);
        ownStop = echo;
        try {
            IDtronChannelValued stop = Dtron.RUN_STOP.constructValued(Map.of());
            if (eventTimeNanos > 0) {
                dtron.send(stop, eventTimeNanos);
            } else {
                dtron.send(stop);
            }
        } catch (DtronException | IllegalStateException e) {
            LOG.warn("Cannot publish the end of the run: {}", e.getMessage());
            return;
        }
        try {
            if (!echo.await(STOP_ECHO_TIMEOUT.toMillis(), TimeUnit.MILLISECONDS)) {
                LOG.warn("The end of the run did not come back from the bus within {} ms; the counters may miss"
                        + " the last messages", STOP_ECHO_TIMEOUT.toMillis());
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /**
     * Before the engine declares a deadline missed: probes the adapter members of the run (they answer from their
     * own threads as long as their processes run and reach the bus); those that do not answer within {@link
     * #PROBE_TIMEOUT} are named as the reason the system may not have acted. The answers also flush what the
     * members sent before them, so an output still in transit is delivered before the engine decides.
     */
    public Optional<String> unreachable() {
        List<String> expected = dtron.getMembers().stream().filter(watched::contains).toList();
        if (expected.isEmpty()) {
            return Optional.empty();
        }
        Set<String> answered;
        try {
            answered = tester.probe(expected, PROBE_TIMEOUT);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return Optional.of("the tester was interrupted while it asked the adapters whether they are there");
        }
        List<String> silent = expected.stream().filter(m -> !answered.contains(m)).toList();
        if (silent.isEmpty()) {
            return Optional.empty();
        }
        return Optional.of("adapter member" + (silent.size() == 1 ? " " : "s ") + String.join(", ", silent)
                + (silent.size() == 1 ? " does" : " do") + " not answer (asked for " + PROBE_TIMEOUT.toMillis()
                + " ms): stopped, overloaded or cut off from the bus");
    }

    /** Returns t2 - t1 of the outputs received from other members so far. */
    public LatencySummary outputLatency() {
        return outputLatency.summary();
    }

    /** Returns t2 - t1 of this run's own inputs, received back from the bus so far. */
    public LatencySummary inputLatency() {
        return inputLatency.summary();
    }

    /**
     * Returns how many outputs came after the end of the run ({@link #stop()}) so far: they are not judged, and
     * are counted here rather than logged, since they follow the verdict.
     */
    public long outputsAfterEnd() {
        return outputsAfterEnd.get();
    }

    /** Returns the bus counters of this run: published, accepted and rejected messages, by reason. */
    public DtronStats stats() {
        return dtron.getStats();
    }

    /** Leaves the bus; closing twice does nothing. */
    @Override
    public void close() {
        dtron.close();
    }

    /** Publishes a message; returns it as published, or null when the bus did not take it (the run then ends). */
    private IDtronChannelValued publish(IDtronChannelValued message, String what) {
        try {
            return dtron.send(message);
        } catch (DtronException | IllegalStateException e) {
            return cannotPublish(what, e);
        }
    }

    private IDtronChannelValued publishAhead(IDtronChannelValued message, long dueEpochNanos, String what) {
        try {
            return tester.sendAhead(message, dueEpochNanos);
        } catch (DtronException | IllegalStateException e) {
            return cannotPublish(what, e);
        }
    }

    /** The bus did not take a message: the run ends INCONCLUSIVE saying so. */
    private IDtronChannelValued cannotPublish(String what, RuntimeException e) {
        LOG.warn("Cannot publish {}: {}", what, e.getMessage());
        context.inconclusive("cannot publish " + what + " on the bus: " + e.getMessage());
        return null;
    }

    /**
     * Returns how many messages of other runs (another tester's, on the same bus) this run ignored so far: they
     * are neither counted as outputs nor judged.
     */
    public long messagesOfOtherRuns() {
        return otherRuns.get();
    }

    /** Whether a message belongs to another run than this run's: it carries another run's id. */
    private boolean ofOtherRun(IDtronChannelValued message) {
        String id = message.getRunId();
        if (id.isEmpty() || id.equals(runId)) {
            return false; // senders that know no run id (older adapters) are taken as this run's
        }
        otherRuns.incrementAndGet();
        otherRunMembers.add(message.getSender());
        LOG.debug("Ignored {} of run {}: this run is {}", message, id, runId);
        return true;
    }

    /**
     * Returns the latest estimate each adapter member sent of this tester's clock minus its own, with its error
     * bound, by member (in member order); members that sent none are left out.
     */
    public Map<String, ClockOffset> clockOffsets() {
        return Collections.unmodifiableMap(new TreeMap<>(offsets));
    }

    /** Keeps the clock offset estimate a member's message carries, for {@link #clockOffsets()}. */
    private void recordOffset(IDtronChannelValued message) {
        if (message.getClockErrorNanos() > 0) {
            offsets.put(message.getSender(), new ClockOffset(dtron.getMemberId(), message.getClockOffsetNanos(),
                    message.getClockErrorNanos()));
        }
    }

    /** An adapter applied one of this run's inputs: the engine places the input at that time. */
    private void acknowledged(IDtronChannelValued ack) {
        if (!running || ofOtherRun(ack)) {
            return;
        }
        if (!ack.getAckedSender().equals(dtron.getMemberId())) {
            IDtronChannelValued held = heldPeerInputs.remove(ack.getAckedSender() + "/" + ack.getAckedSequence());
            if (held != null) {
                recordOffset(ack);
                reportOutput(held, ack); // another tester's input, observed where its adapter applied it
            }
            return;
        }
        // the first acknowledgement of an input counts: one member applies it
        Long number;
        synchronized (inputNumbers) {
            number = inputNumbers.remove(ack.getAckedSequence());
        }
        recordOffset(ack);
        if (number != null) {
            long applied = timeline.eventMicros(ack);
            SentInput sent = sentInputs.remove(number);
            String channel = sent == null ? "?" : sent.channel();
            if (sent != null) {
                measured("input", channel, applied - sent.sentMicros());
                if (sent.dueMicros() >= 0) {
                    inputDelays.appliedAhead(channel, sent.sentMicros(), sent.dueMicros(), applied,
                            RunTimeline.errorMicros(ack));
                } else {
                    inputDelays.applied(channel, applied - sent.sentMicros(), RunTimeline.errorMicros(ack));
                }
            }
            arrived(ack, "acknowledgement of " + channel, applied);
            context.inputApplied(number, applied, RunTimeline.errorMicros(ack));
        }
    }

    /** Called on the bus's listener thread, in the bus's order. */
    private void received(IDtronChannelValued message) {
        String channel = message.getChannelName();
        if (message.getSender().equals(dtron.getMemberId())) {
            inputLatency.record(message);
            return;
        }
        if (ofOtherRun(message)) {
            return;
        }
        if (!outputs.contains(channel)) {
            LOG.warn("Ignored {}: '{}' is an input, which only the tester publishes", message, channel);
            if (running && !notOwners().contains(message.getSender()) && !isPeerTester(message.getSender())) {
                context.inconclusive(ChannelOwners.inputSent(channel, message.getSender(), served));
            }
            return;
        }
        outputLatency.record(message);
        if (!running && context != null) {
            outputsAfterEnd.incrementAndGet();
            LOG.debug("Ignored output {}: the run is over", message);
            return;
        }
        if (!running) {
            if (warnedBeforeStart.compareAndSet(false, true)) {
                LOG.warn("Ignored output {}: the run has not started (more such outputs are logged at debug level)",
                        message);
            } else {
                LOG.debug("Ignored output {}: the run has not started", message);
            }
            return;
        }
        Optional<String> notOwner = owners.notOwner(channel, message.getSender(), served, notOwners());
        if (notOwner.isPresent()) {
            LOG.warn("Not judged: {}: {}", message, notOwner.get());
            context.inconclusive(notOwner.get());
            return;
        }
        recordOffset(message);
        if (isPeerTester(message.getSender()) && appliedByAdapter(message.getChannelName())) {
            // another tester's input, which an adapter applies: it happened where the adapter applied it, which its
            // acknowledgement says; held for half the reorder window, then taken as happened when published
            String key = message.getSender() + "/" + message.getSequence();
            heldPeerInputs.put(key, message);
            context.clock().schedule(window.micros() / 2, () -> {
                IDtronChannelValued unacknowledged = heldPeerInputs.remove(key);
                if (unacknowledged != null && running) {
                    reportOutput(unacknowledged, unacknowledged);
                }
            });
            return;
        }
        reportOutput(message, message);
    }

    /** Reports an output to the engine at the event time {@code timing} carries (itself, or its acknowledgement). */
    private void reportOutput(IDtronChannelValued message, IDtronChannelValued timing) {
        // stamped before time 0 (it was ordered before the start on the bus): it counts from the start
        long happened = Math.max(0, timeline.eventMicros(timing));
        measured("output", message.getChannelName(), timeline.arrivalDelay(timing, happened));
        arrived(timing, "output " + message.getChannelName(), happened);
        context.report(new Event(message.getChannelName(), message.getVariables()), happened,
                RunTimeline.errorMicros(timing));
    }

    /** Whether an adapter (a member that is no tester of this run) listens to a channel, so applies its messages. */
    private boolean appliedByAdapter(String channel) {
        return tester.getMembersServedChannels().values().stream().anyMatch(served -> served.receives()
                .contains(channel) && !isPeerTester(served.member()));
    }

    /** Whether a member is another tester of this run. */
    private boolean isPeerTester(String member) {
        return runTesters.isPeer(member);
    }

    /** Adds a delay to a channel's interval in one direction. */
    private void measured(String direction, String channel, long delayMicros) {
        runDelays.merge(direction + " " + channel, new ChannelDelay(channel, direction, 1, Math.max(0, delayMicros),
                Math.max(0, delayMicros)), (old, one) -> old.plus(delayMicros));
    }

    /**
     * A message arrived: widens the reorder window when it took more than half of it and the window is automatic.
     */
    private void arrived(IDtronChannelValued message, String what, long eventRunMicros) {
        window.arrived(timeline.arrivalDelay(message, eventRunMicros), timeline.receivedMicros(message),
                what + " from " + message.getSender()).ifPresent(context::widenReorderWindow);
    }

    /**
     * Called on the bus's listener thread, after the messages of members that left. Only members that served the run
     * when it started count (see {@link #startRun}): this news may come after the start for a member that left
     * before, and a member that joined during the run never served it (a tester refused because this run is going
     * on, its adapters, an observer), nor did one that serves no channel of the model, so its leaving does not end
     * the run.
     */
    private void membershipChanged(List<String> members, List<String> joined, List<String> left) {
        if (!joined.isEmpty()) {
            LOG.info("Joined the bus: {}; members now {}", joined, members);
        }
        if (left.isEmpty()) {
            return;
        }
        LOG.info("Left the bus: {}; members now {}", left, members);
        // a tester of another run (refused because of this one) never served it, even if it said so only now
        List<String> gone = left.stream().filter(watched::remove)
                .filter(m -> !tester.wasTester(m) || m.equals(runTesters.leader())).toList();
        if (running && !gone.isEmpty()) {
            gone.forEach(runMembers::left); // reported here, not again by the start
            context.inconclusive("adapter member" + (gone.size() == 1 ? " " : "s ") + String.join(", ", gone)
                    + " left the bus (members now " + members + "); the system under test may be gone");
        }
    }

    /**
     * An input the run published: its channel, when it was published and when it is due (on the run's clock in
     * microseconds; -1 for an input published at its time).
     */
    private record SentInput(String channel, long sentMicros, long dueMicros) {
    }
}
