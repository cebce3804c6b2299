package io.dtron.api;

import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.api.internal.BusConnector;
import io.dtron.api.internal.ChannelHandshake;
import io.dtron.api.internal.ClockSync;
import io.dtron.api.internal.Counters;
import io.dtron.api.internal.DtronChannel;
import io.dtron.api.internal.DtronChannelValued;
import io.dtron.api.internal.HostClock;
import io.dtron.api.internal.SerialExecutor;
import io.dtron.api.internal.Stamp;
import io.dtron.api.internal.SyncCodec;
import io.dtron.api.internal.TesterSide;
import io.dtron.api.internal.TestHooks;
import io.dtron.api.internal.proto.Sync;
import io.dtron.bus.internal.BusMessage;
import io.dtron.bus.internal.MembershipView;
import io.dtron.bus.internal.Subscription;
import io.dtron.bus.internal.Transport;
import io.dtron.bus.internal.BindAddressException;
import io.dtron.bus.internal.BusKeys;
import io.dtron.bus.internal.EpochClock;
import io.dtron.bus.internal.PortsInUseException;
import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Collection;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * One member of a DTRON bus: sends channel messages and calls
 * {@link DtronListener listeners} with the messages of their channels.
 *
 * <p>Every member receives every message, its own included, in one total
 * order that is the same at all members. A received message that is no valid
 * {@code Sync}, names an unknown channel (for a member with declared
 * channels: one neither it nor another tester on the bus serves), or carries
 * unknown or missing variables is rejected: logged with the reason, counted in
 * {@link #getStats()}, and not delivered; later messages are delivered as
 * usual. {@link DtronMembershipListener Membership listeners} learn who joins
 * and leaves. Thread-safe.
 */
public final class Dtron implements AutoCloseable {
    /**
     * The channel on which a tester announces that a test run starts, with the run's time unit in microseconds
     * as variable {@code timeunit}. Time 0 of the run is when the tester published it: an adapter whose system
     * acts on its own (a ticker, a timeout) starts its clock when this message arrives. A model channel may not
     * have this name.
     */
    public static final IDtronChannel RUN_START = IDtronChannel.of("dtron_start", "timeunit");

    /**
     * The channel on which a tester announces that its test run is over, whatever the verdict: an adapter whose
     * system acts on its own stops it until the next {@link #RUN_START}, so that nothing it does between runs is
     * taken for the next run's. A model channel may not have this name.
     */
    public static final IDtronChannel RUN_STOP = IDtronChannel.of("dtron_stop");

    /**
     * The channel of acknowledgements, without variables: a member acknowledges an input of the current run's
     * tester when it has applied it, with {@link IDtronChannelValued#getAckedSender()} and
     * {@link IDtronChannelValued#getAckedSequence()} naming the input and the
     * {@linkplain IDtronChannelValued#getEventTimeNanos() event time} telling when it was applied, on the
     * acknowledging member's clock (whose {@linkplain IDtronChannelValued#getClockOffsetNanos() offset} to the
     * tester's clock the acknowledgement carries). By default a member acknowledges an input when its last
     * listener of the input's channel returned (see {@link DtronListener#autoAcknowledge()} and
     * {@link #acknowledge(IDtronChannelValued, long)}); a tester listens to this channel. Only {@code Dtron}
     * publishes on it, and {@link #getStats()} does not count acknowledgements. A model channel may not have this
     * name.
     */
    public static final IDtronChannel ACK = IDtronChannel.of("dtron_ack");

    /**
     * The channel on which each tester of a run of several testers tells the others its verdict, as variable {@code
     * verdict}: 0 PASSED, 2 FAILED, 3 INCONCLUSIVE (the exit codes of {@code dtron run}). A tester still running
     * ends its own run INCONCLUSIVE when another one ended FAILED or INCONCLUSIVE. A model channel may not have this
     * name.
     */
    public static final IDtronChannel RUN_VERDICT = IDtronChannel.of("dtron_verdict", "verdict");

    /**
     * The channel on which a monitor ({@code dtron monitor --cluster/--bus}) publishes its alarms and its final
     * verdict, for a safety controller to act on: {@code number} (the violation's number in the run; on the verdict
     * the number of violations), {@code reason} (0 none, 1 an unexpected event, 2 wrong values, 3 a missed deadline),
     * {@code channel} (the violating event's channel, as its 1-based position among the model's inputs and then
     * outputs; 0 for none), {@code sequence} (its message's sequence number from its sender; 0 for none), {@code
     * withheld} (1 when a shield withheld the message) and {@code verdict} (0 an alarm, 1 the final verdict). The
     * message's event time is the alarm's time. A model channel may not have this name.
     */
    public static final IDtronChannel ALARM = IDtronChannel.of("dtron_alarm", "number", "reason", "channel",
            "sequence", "withheld", "verdict");

    /**
     * The channel on which a model version is handed to a controller that runs on the bus and takes versions from
     * it ({@code dtron control --reload-from-bus}): variable {@code version}, the sender's number for it, which the
     * {@link #MODEL_OUTCOME} answering it carries; the version itself in the message's {@linkplain
     * IDtronChannelValued#getText() text}, a JSON object with {@code label}, {@code model} (the text of an
     * {@code .xml} or {@code .xta} model) and {@code queries} (the text of its {@code .q}), sent with {@link
     * #send(IDtronChannelValued, String)}. A controller honours it only on a bus with a secret. A model channel may
     * not have this name.
     */
    public static final IDtronChannel MODEL_VERSION = IDtronChannel.of("dtron_model", "version");

    /**
     * The channel on which a controller says what became of a {@link #MODEL_VERSION}: variable {@code version}, the
     * number of the version it answers, and {@code outcome}: 0 taken at a reset point, 1 accepted (it passed the
     * check and waits for the next reset point), 2 refused; the message's {@linkplain IDtronChannelValued#getText()
     * text} says what happened, a refusal with its reason. A model channel may not have this name.
     */
    public static final IDtronChannel MODEL_OUTCOME = IDtronChannel.of("dtron_model_outcome", "version", "outcome");

    /** DTRON's channels, by name: the public ones and those of the clock-offset protocol. */
    private static final Map<String, DtronChannel> RESERVED = Map.ofEntries(
            Map.entry(RUN_START.getChannelName(), DtronChannel.copyOf(RUN_START)),
            Map.entry(RUN_STOP.getChannelName(), DtronChannel.copyOf(RUN_STOP)),
            Map.entry(ACK.getChannelName(), DtronChannel.copyOf(ACK)),
            Map.entry(RUN_VERDICT.getChannelName(), DtronChannel.copyOf(RUN_VERDICT)),
            Map.entry(MODEL_VERSION.getChannelName(), DtronChannel.copyOf(MODEL_VERSION)),
            Map.entry(MODEL_OUTCOME.getChannelName(), DtronChannel.copyOf(MODEL_OUTCOME)),
            Map.entry(ALARM.getChannelName(), DtronChannel.copyOf(ALARM)),
            Map.entry(ClockSync.HELLO, new DtronChannel(ClockSync.HELLO, List.of())),
            Map.entry(ClockSync.PING, new DtronChannel(ClockSync.PING, List.of())),
            Map.entry(ClockSync.PONG, new DtronChannel(ClockSync.PONG, List.of())),
            Map.entry(ChannelHandshake.SERVE, new DtronChannel(ChannelHandshake.SERVE, List.of())));
    /** DTRON's channels whose messages carry a text. */
    private static final Set<String> TEXT = Set.of(MODEL_VERSION.getChannelName(), MODEL_OUTCOME.getChannelName());
    /** The channels only Dtron itself sends on and listens to. */
    private static final Set<String> CONTROL = Set.of(ClockSync.HELLO, ClockSync.PING, ClockSync.PONG,
            ChannelHandshake.SERVE);
    /** The channel of the message {@code Dtron} hands its own dispatcher when it starts; never on the bus. */
    private static final DtronChannel WARM_UP = new DtronChannel("dtron_warm_up", List.of());
    /** How many acknowledged messages a member remembers, so as to acknowledge each once. */
    private static final int ACKED_MEMORY = 65_536;

    private static final Logger LOG = LoggerFactory.getLogger(Dtron.class);

    static {
        TesterSide.Access.grant(dtron -> dtron.testerSide);
    }
    private static final Duration CLOSE_TIMEOUT = Duration.ofSeconds(5);
    /** How long {@link #connect} waits at most for the warm-up of the run clock's code (see RunClock.warmUp). */
    private static final Duration RUN_CLOCK_WARM_UP = Duration.ofMillis(200);

    private final Transport transport;
    private final String clusterName;
    private final Optional<Map<String, DtronChannel>> declared;
    private final Map<String, Registration> registrations = new ConcurrentHashMap<>();
    /** On a tester: the delays of the other members' messages, by member. */
    private final Map<String, MemberDelay> delays = new ConcurrentHashMap<>();
    private final List<DtronMembershipListener> membershipListeners = new CopyOnWriteArrayList<>();
    private final List<java.util.function.Consumer<BusRecord>> recordListeners = new CopyOnWriteArrayList<>();
    private final List<java.util.function.Consumer<Map<String, ServedChannels>>> servedListeners =
            new CopyOnWriteArrayList<>();
    private final Counters counters = new Counters();
    /** The listeners that may be called on the transport's receiving thread ({@link DtronListener#onReceivingThread}). */
    private final Set<DtronListener> onReceivingThread = ConcurrentHashMap.newKeySet();
    /**
     * On the run clock's thread while it hands an input sent ahead to the listeners ({@link #deliverWhenDue}): the
     * acknowledgements they make, published by the listeners' thread after them.
     */
    private final ThreadLocal<List<Runnable>> deferredAcks = new ThreadLocal<>();
    /** The members that said in the handshake that they hold inputs sent ahead until they are due. */
    private final Set<String> holdingMembers = ConcurrentHashMap.newKeySet();
    private final AtomicLong sequence = new AtomicLong();
    private final SerialExecutor dispatcher;
    private final Object lock = new Object();
    private final Subscription viewSubscription;
    private final Optional<Subscription> allGroups;
    private final List<Subscription> ownGroups;
    private final long clockShiftNanos;
    /** The id of the wall clock this member reads ({@link HostClock}), or "" when it is shifted for a test. */
    private final String hostClock;
    private final ClockSync clockSync;
    private final ChannelHandshake handshake;
    /** The other members that said they are testers while on the bus (see {@link TesterSide#wasTester}); only grows. */
    private final Set<String> testersSeen = ConcurrentHashMap.newKeySet();
    private final RunClock runClock;
    /** What only a tester does with this member (see {@link TesterSide#of}). */
    private final TesterSide testerSide = new TesterSide() {
        @Override
        public void setRunId(String id) {
            runIdSet = Objects.requireNonNull(id, "id");
        }

        @Override
        public IDtronChannelValued sendRunStart(IDtronChannelValued start, long zeroEpochNanos, long endEpochNanos) {
            if (!start.getChannelName().equals(RUN_START.getChannelName()) || zeroEpochNanos <= 0
                    || endEpochNanos < 0) {
                throw new IllegalArgumentException("not a run start with positive times: " + start);
            }
            return publish(start, zeroEpochNanos, "", endEpochNanos, 0);
        }

        @Override
        public IDtronChannelValued sendAhead(IDtronChannelValued input, long dueEpochNanos) {
            if (dueEpochNanos <= 0 || RESERVED.containsKey(input.getChannelName())) {
                throw new IllegalArgumentException("not an input of a model channel with a positive due time: "
                        + input);
            }
            return publish(input, 0, "", 0, dueEpochNanos);
        }

        @Override
        public boolean holdsInputs(String member) {
            return holdingMembers.contains(member);
        }

        @Override
        public Set<String> probe(Collection<String> members, Duration timeout) throws InterruptedException {
            return Dtron.this.probe(members, timeout, false);
        }

        @Override
        public Set<String> probeAsInput(Collection<String> members, Duration timeout) throws InterruptedException {
            return Dtron.this.probe(members, timeout, true);
        }

        @Override
        public boolean awaitListeners(Duration timeout) throws InterruptedException {
            return dispatcher.awaitQueued(timeout);
        }

        @Override
        public Set<String> getOtherTesters() {
            Set<String> testers = new LinkedHashSet<>(clockSync.otherTesters());
            handshake.others().values().stream().filter(ServedChannels::tester).map(ServedChannels::member)
                    .forEach(testers::add);
            return Collections.unmodifiableSet(testers);
        }

        @Override
        public boolean wasTester(String member) {
            return testersSeen.contains(member);
        }

        @Override
        public AnnouncedEnd announcedEnd() {
            return announcedEnd;
        }

        @Override
        public Map<String, MemberDelay> getDelaysFromMembers() {
            return Collections.unmodifiableMap(new java.util.TreeMap<>(delays));
        }

        @Override
        public Map<String, ServedChannels> getMembersServedChannels() {
            return handshake.others();
        }

        @Override
        public void addServedChannelsListener(java.util.function.Consumer<Map<String, ServedChannels>> listener) {
            Objects.requireNonNull(listener, "listener");
            synchronized (lock) {
                requireOpen();
                if (!servedListeners.contains(listener)) {
                    servedListeners.add(listener);
                }
            }
        }

        @Override
        public void removeServedChannelsListener(java.util.function.Consumer<Map<String, ServedChannels>> listener) {
            servedListeners.remove(Objects.requireNonNull(listener, "listener"));
        }

        @Override
        public void setJoiningRun(boolean joining) {
            handshake.joiningRun(joining);
        }
    };
    private final Map<AckKey, Boolean> acknowledged = new LinkedHashMap<>() {
        @Override
        protected boolean removeEldestEntry(Map.Entry<AckKey, Boolean> eldest) {
            return size() > ACKED_MEMORY;
        }
    };
    private MembershipView lastView;
    private volatile String runIdSet = "";
    /** The current run's id and tester as of the last message received from the bus, in the bus's order. */
    private volatile String runId = "";
    private volatile String runTester;
    /**
     * The end of the current run its start announced (on the tester's wall clock, 0 for none): the tester's pongs
     * carry it, so that a member that joins during the run learns it ({@link TesterSide#announcedEnd}).
     */
    private volatile long runEndNanos;
    /** The end of the current run as the tester's latest pong to this member said it. */
    private volatile TesterSide.AnnouncedEnd announcedEnd = new TesterSide.AnnouncedEnd("", 0);
    private volatile boolean closed;

    /** A message a member acknowledged. */
    private record AckKey(String sender, long sequence) {
    }

    /** The listeners of one channel and the template their messages must fit. */
    private record Registration(DtronChannel template, List<DtronListener> listeners, Optional<Subscription> group) {
    }

    private Dtron(Transport transport, DtronOptions options) {
        this.transport = transport;
        this.clusterName = options.getClusterName();
        this.declared = options.getChannels().map(channels -> {
            Map<String, DtronChannel> copy = new LinkedHashMap<>();
            channels.forEach((name, channel) -> copy.put(name, DtronChannel.copyOf(channel)));
            return Map.copyOf(copy);
        });
        this.dispatcher = new SerialExecutor("dtron-listeners-" + transport.localMember());
        this.clockShiftNanos = TestHooks.clockShift(options).toNanos();
        this.hostClock = clockShiftNanos == 0 ? HostClock.id() : "";
        this.clockSync = new ClockSync(transport.localMember(), hostClock, options.isTester(), this::currentTimeNanos,
                sequence::incrementAndGet, this::publishControl, this::offsetChanged);
        this.handshake = new ChannelHandshake(transport.localMember(), dispatcher::execute,
                this::publishServed, this::othersServedChanged, options.isTester());
        this.runClock = new RunClock(transport.localMember(), this::currentTimeNanos, this::runClockOffset);
        this.lastView = transport.view();
        this.viewSubscription = transport.addViewListener(this::viewChanged);
        this.allGroups = declared.map(d -> transport.subscribeAll(this::received));
        this.ownGroups = declared.isPresent()
                ? List.of()
                : List.of(RUN_START.getChannelName(), RUN_STOP.getChannelName(), ClockSync.HELLO, ClockSync.PING,
                        ClockSync.PONG, ChannelHandshake.SERVE).stream().map(group -> transport.subscribe(group, this::received)).toList();
        // a message's way to the listeners, taken once now rather than by a run's first message: no listener hears it
        dispatch(WARM_UP.constructValued(Map.of()), false);
        clockSync.start();
    }

    /**
     * Returns whether DTRON reserves a channel name for itself: {@link #RUN_START}, {@link #RUN_STOP},
     * {@link #ACK}, {@link #RUN_VERDICT}, {@link #ALARM}, the channels of the clock-offset protocol ({@code dtron_hello}, {@code dtron_ping},
     * {@code dtron_pong}) and of the channel-serving handshake ({@code dtron_serve}). No model channel may have such
     * a name.
     */
    public static boolean isReservedChannel(String channelName) {
        return RESERVED.containsKey(Objects.requireNonNull(channelName, "channelName"));
    }

    /**
     * Checks a declared template: a reserved name is allowed only for {@link #RUN_START} and {@link #RUN_STOP}
     * themselves, which a tester declares with its model's channels.
     *
     * @throws IllegalArgumentException if the channel has a reserved name and is not one of those two
     */
    static void checkNotReserved(IDtronChannel channel) {
        String name = channel.getChannelName();
        DtronChannel reserved = RESERVED.get(name);
        boolean runChannel = name.equals(RUN_START.getChannelName()) || name.equals(RUN_STOP.getChannelName())
                || name.equals(RUN_VERDICT.getChannelName());
        if (reserved != null && (!runChannel || !reserved.isCompatible(channel))) {
            throw new IllegalArgumentException("channel '" + channel.getChannelName() + "' is reserved by DTRON"
                    + " (for the start and end of runs, acknowledgements and clock offsets); a model channel may not"
                    + " have this name");
        }
    }

    /**
     * Joins the bus with the default options: cluster {@value DtronOptions#DEFAULT_CLUSTER} on loopback.
     *
     * @throws DtronException if the bus cannot be joined
     */
    public static Dtron connect() {
        return connect(DtronOptions.builder().build());
    }

    /**
     * Joins the bus.
     *
     * @throws DtronException if the bus cannot be joined, for instance because the
     *                        key file cannot be read or created, the ports of the
     *                        options are in use or the bind address is not
     *                        this host's (the message says which, in one line)
     */
    public static Dtron connect(DtronOptions options) {
        Objects.requireNonNull(options, "options");
        SyncCodec.warmUp();
        RunClock.warmUp(RUN_CLOCK_WARM_UP);
        Transport transport;
        try {
            transport = BusConnector.connect(options);
        } catch (PortsInUseException | BindAddressException | BusKeys.KeyFileException e) {
            // the message says it all, in one line: which ports or key file, and what to do
            throw new DtronException("cannot join bus '" + options.getClusterName() + "': " + e.getMessage(), null);
        } catch (Exception e) {
            throw new DtronException("cannot join bus " + options, e);
        }
        try {
            Dtron dtron = new Dtron(transport, options);
            LOG.info("Joined bus '{}' as {}; members {}", dtron.clusterName, dtron.getMemberId(), dtron.getMembers());
            return dtron;
        } catch (RuntimeException | Error e) {
            transport.close();
            throw e;
        }
    }

    /**
     * Adds a listener for its channel. Messages that arrive from now on are
     * delivered to it; a listener added twice is called once.
     *
     * @throws IllegalArgumentException if the channel has a different template
     *                                  here (or is not declared, when channels are declared)
     * @throws IllegalStateException    if the listener belongs to another {@code Dtron}, or this one is closed
     */
    public void addDtronListener(DtronListener listener) {
        Objects.requireNonNull(listener, "listener");
        DtronChannel template = DtronChannel.copyOf(listener.getChannel());
        String name = template.getChannelName();
        if (CONTROL.contains(name)) {
            throw new IllegalArgumentException("channel '" + name + "' is DTRON's own; no listener can be added");
        }
        synchronized (lock) {
            requireOpen();
            Registration registration = registrations.get(name);
            DtronChannel known = registration != null
                    ? registration.template()
                    : RESERVED.containsKey(name)
                            ? RESERVED.get(name)
                            : declared.map(d -> requireDeclared(d, name)).orElse(template);
            if (!known.isCompatible(template)) {
                throw new IllegalArgumentException("listener template " + template + " differs from " + known);
            }
            if (!listener.attach(this)) {
                throw new IllegalStateException("listener " + listener + " belongs to another Dtron");
            }
            if (registration == null) {
                Optional<Subscription> group = declared.isPresent() || name.equals(RUN_START.getChannelName())
                        || name.equals(RUN_STOP.getChannelName())
                        ? Optional.empty()
                        : Optional.of(transport.subscribe(name, this::received));
                registration = new Registration(known, new CopyOnWriteArrayList<>(), group);
                registrations.put(name, registration);
            }
            if (!registration.listeners().contains(listener)) {
                if (asksReceivingThread(listener)) {
                    onReceivingThread.add(listener);
                }
                registration.listeners().add(listener);
            }
        }
        // a listener that only observes (a monitor's) does not make this member serve the channel
        if (!RESERVED.containsKey(name) && listener.serves()) {
            handshake.receiving(name, true);
        }
    }

    /** Removes a listener; it receives no further messages. Removing an unknown listener does nothing. */
    public void removeDtronListener(DtronListener listener) {
        Objects.requireNonNull(listener, "listener");
        synchronized (lock) {
            String name = listener.getChannel().getChannelName();
            Registration registration = registrations.get(name);
            if (registration == null || !registration.listeners().remove(listener)) {
                return;
            }
            onReceivingThread.remove(listener);
            listener.detach(this);
            if (registration.listeners().isEmpty()) {
                registrations.remove(name);
                registration.group().ifPresent(Subscription::close);
                handshake.receiving(name, false);
            }
        }
    }

    /**
     * Declares the channels this member publishes (a tester's outputs), so that a tester waiting until every
     * channel of its model is served knows before this member sends the first message on them. The channels this
     * member listens to are declared by {@link #addDtronListener}, and a channel it sends on is added when it first
     * does; declaring twice does nothing. Members tell each tester that greets the bus, and tell the bus again
     * whenever the channels change (see {@link #getServedChannels()}).
     *
     * @throws IllegalArgumentException if a channel is one DTRON reserves
     */
    public void declareOutputs(IDtronChannel... channels) {
        declareOutputs(List.of(channels));
    }

    /**
     * Declares the channels this member publishes; see {@link #declareOutputs(IDtronChannel...)}.
     *
     * @throws IllegalArgumentException if a channel is one DTRON reserves
     */
    public void declareOutputs(Collection<? extends IDtronChannel> channels) {
        List<String> names = new ArrayList<>();
        for (IDtronChannel channel : channels) {
            String name = Objects.requireNonNull(channel, "channel").getChannelName();
            if (RESERVED.containsKey(name)) {
                throw new IllegalArgumentException("channel '" + name + "' is DTRON's own; it is not served");
            }
            names.add(name);
        }
        handshake.sending(names);
    }

    /**
     * Returns the channels this member serves: those it has listeners for and those it declared or sent on (for a
     * tester, those it tests, and that it is a tester). It tells the bus whenever they change, and each tester that
     * greets the bus.
     */
    public ServedChannels getServedChannels() {
        return handshake.own();
    }

    /**
     * Adds a listener that receives a {@link BusRecord} of every later message this member receives, in the bus's
     * order, DTRON's own messages included, for traces. A member with {@linkplain DtronOptions.Builder#channels
     * declared channels} (a tester) receives every message on the bus: those on its own channels, on the channels
     * another tester on the bus serves (its model's, named in the handshake) and DTRON's, but not those it rejects;
     * others receive the channels they listen to and DTRON's. The listener is called on the transport's thread: it
     * must return quickly and not throw.
     */
    public void addRecordListener(java.util.function.Consumer<BusRecord> listener) {
        recordListeners.add(Objects.requireNonNull(listener, "listener"));
    }

    /** Removes a record listener; removing an unknown one does nothing. */
    public void removeRecordListener(java.util.function.Consumer<BusRecord> listener) {
        recordListeners.remove(listener);
    }

    /**
     * Adds a listener that is told about every later change of the members; a listener added twice is called
     * once. It is called on the thread of the {@link DtronListener}s, in order with the messages: a member's
     * messages come before the news that it left.
     */
    public void addMembershipListener(DtronMembershipListener listener) {
        Objects.requireNonNull(listener, "listener");
        synchronized (lock) {
            requireOpen();
            if (!membershipListeners.contains(listener)) {
                membershipListeners.add(listener);
            }
        }
    }

    /** Removes a membership listener; removing an unknown one does nothing. */
    public void removeMembershipListener(DtronMembershipListener listener) {
        membershipListeners.remove(Objects.requireNonNull(listener, "listener"));
    }

    /**
     * Publishes a message to every member, stamped with this member's id, the next sequence number, the publish
     * time as event time, the run id ({@link TesterSide#setRunId}) and this member's clock offset estimate.
     *
     * @throws InvalidMessageException  if the channel is not declared (when channels are declared) or its
     *                                  variables do not fit the template known here
     * @throws IllegalArgumentException if the channel is {@link #ACK} or another channel only DTRON sends on
     * @return the message as published: with this member as sender, its sequence number, publish and event time,
     *         run id and clock offset (and receive time 0), so that a tester can match acknowledgements to it
     * @throws IllegalStateException    if this {@code Dtron} is closed
     * @throws DtronException           if the bus did not take the message
     */
    public IDtronChannelValued send(IDtronChannelValued message) {
        return publish(message, 0);
    }

    /**
     * Publishes a message, as {@link #send(IDtronChannelValued)} does, for an event that happened earlier: an
     * output that the system under test produced at {@code eventTimeEpochNanos}. The tester takes the output as
     * happened then (on its clock: the event time plus this member's clock offset estimate), not when the message
     * arrived.
     *
     * @param eventTimeEpochNanos when the event happened on this member's wall clock, in nanoseconds since the
     *                            epoch (as {@link #currentTimeNanos()} reads it)
     * @return the message as published
     * @throws IllegalArgumentException if the event time is not positive, or the channel is one only DTRON
     *                                  sends on
     * @see #send(IDtronChannelValued)
     */
    public IDtronChannelValued send(IDtronChannelValued message, long eventTimeEpochNanos) {
        if (eventTimeEpochNanos <= 0) {
            throw new IllegalArgumentException("event time must be positive: " + eventTimeEpochNanos);
        }
        return publish(message, eventTimeEpochNanos);
    }

    /**
     * Publishes a message with a text, as {@link #send(IDtronChannelValued)} does: on DTRON's channels that carry
     * one, {@link #MODEL_VERSION} and {@link #MODEL_OUTCOME}.
     *
     * @return the message as published
     * @throws IllegalArgumentException if the channel carries no text
     * @see #send(IDtronChannelValued)
     */
    public IDtronChannelValued send(IDtronChannelValued message, String text) {
        Objects.requireNonNull(text, "text");
        if (!TEXT.contains(Objects.requireNonNull(message, "message").getChannelName())) {
            throw new IllegalArgumentException("channel '" + message.getChannelName() + "' carries no text");
        }
        return publish(message, 0, text, 0, 0);
    }

    /**
     * Acknowledges an input now: publishes on {@link #ACK} that this member applied it at {@link
     * #currentTimeNanos()}. For a listener that does not leave this to the {@code Dtron} (see {@link
     * DtronListener#autoAcknowledge()}).
     *
     * @return true if the acknowledgement was published, false if this member had acknowledged the message before
     * @see #acknowledge(IDtronChannelValued, long)
     */
    public boolean acknowledge(IDtronChannelValued message) {
        return acknowledge(message, currentTimeNanos());
    }

    /**
     * Acknowledges an input: publishes on {@link #ACK} that this member applied it at {@code
     * appliedAtEpochNanos}. A member acknowledges each message once; a message it acknowledged before (itself or
     * automatically when its listeners returned) is not acknowledged again. Called by a listener on the bus's
     * receiving thread ({@link DtronListener#onReceivingThread}), or on an input sent ahead of its time (handed to the
     * listeners by the run clock's thread), it publishes once the listener has returned, and a failure then is
     * logged.
     *
     * @param message             a message received from the bus, on a channel of the model
     * @param appliedAtEpochNanos when the input took effect, on this member's wall clock in nanoseconds since the
     *                            epoch (as {@link #currentTimeNanos()} reads it)
     * @return true if the acknowledgement was published, false if this member had acknowledged the message before
     * @throws IllegalArgumentException if the message did not come from the bus (it has no sender or sequence
     *                                  number), is on a channel DTRON reserves, or the time is not positive
     * @throws IllegalStateException    if this {@code Dtron} is closed
     * @throws DtronException           if the bus did not take the acknowledgement
     */
    public boolean acknowledge(IDtronChannelValued message, long appliedAtEpochNanos) {
        Objects.requireNonNull(message, "message");
        if (message.getSender().isEmpty() || message.getSequence() <= 0) {
            throw new IllegalArgumentException("only a message received from the bus can be acknowledged: " + message);
        }
        if (isReservedChannel(message.getChannelName())) {
            throw new IllegalArgumentException("a message on DTRON's channel '" + message.getChannelName()
                    + "' is not acknowledged");
        }
        if (appliedAtEpochNanos <= 0) {
            throw new IllegalArgumentException("time must be positive: " + appliedAtEpochNanos);
        }
        requireOpen();
        if (acknowledgesAfterListener()) {
            if (!claimAck(message)) {
                return false;
            }
            acknowledgeAfterListener(message, appliedAtEpochNanos);
            return true;
        }
        return publishAck(message, appliedAtEpochNanos);
    }

    /** Returns the run id this member stamps on the messages it sends now (see {@link TesterSide#setRunId}), or "". */
    public String getRunId() {
        String set = runIdSet;
        return set.isEmpty() ? runId : set;
    }

    /**
     * Returns this member's wall clock in nanoseconds since the epoch, as it stamps messages: {@link
     * java.time.Instant#now()}, plus the shift of {@link TestHooks#clockShift(DtronOptions.Builder, Duration)} in tests.
     */
    public long currentTimeNanos() {
        return EpochClock.nowNanos() + clockShiftNanos;
    }

    /**
     * Returns this member's clock for the current run: the run's time on the tester's clock, and tasks scheduled
     * at run times.
     */
    public RunClock runClock() {
        return runClock;
    }

    /**
     * Returns the tester this member knows: the sender of the last {@link #RUN_START}, or a member connected as
     * the {@linkplain DtronOptions.Builder#tester tester}, while it is on the bus. This member if it is the tester.
     */
    public Optional<String> getTester() {
        return clockSync.tester();
    }

    private Set<String> probe(Collection<String> members, Duration timeout, boolean asInput)
            throws InterruptedException {
        long deadline = System.nanoTime() + timeout.toNanos();
        Set<String> answered = new LinkedHashSet<>(clockSync.probe(members, timeout, asInput));
        answered.retainAll(members);
        // what the members sent before their answers is delivered once the listeners' queue has passed this point
        dispatcher.awaitQueued(Duration.ofNanos(Math.max(0, deadline - System.nanoTime())));
        return answered;
    }

    /**
     * Returns this member's estimate of how far the tester's wall clock is from its own: from the ping with the
     * shortest round trip among the last few to the tester it knows (see {@link #getTester()}), exact on the
     * tester itself; empty before the first ping came back, or when it knows no tester. Members ping the tester
     * when they learn of it and about once a second afterwards, so the estimate changes; this one value is
     * consistent.
     */
    public Optional<ClockOffset> getClockOffset() {
        return clockSync.estimate();
    }

    /** Returns whether this member has an estimate of the tester's clock: {@code getClockOffset().isPresent()}. */
    public boolean hasClockOffset() {
        return clockSync.estimate().isPresent();
    }

    /**
     * Returns this member's current estimate of (the tester's wall clock - its own wall clock) in nanoseconds; 0
     * when there is none or this member is the tester. Use {@link #getClockOffset()} for an offset and its error
     * bound from the same estimate.
     */
    public long getClockOffsetNanos() {
        return runClockOffset();
    }

    /**
     * Returns the error bound of the current estimate in nanoseconds: half the round trip of the ping it comes
     * from (the true offset is within this of the estimate); 0 when there is no estimate or this member is the
     * tester. Use {@link #getClockOffset()} for an offset and its error bound from the same estimate.
     */
    public long getClockErrorNanos() {
        return clockSync.estimate().map(ClockOffset::errorNanos).orElse(0L);
    }

    /** Returns this member's id on the bus, which every message it sends carries. */
    public String getMemberId() {
        return transport.localMember();
    }

    /** Returns the ids of the members on the bus now, oldest first; immutable. */
    public List<String> getMembers() {
        return transport.view().members();
    }

    /**
     * Waits until at least {@code count} members are on the bus.
     *
     * @return whether they were, before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean awaitMembers(int count, Duration timeout) throws InterruptedException {
        long deadline = System.nanoTime() + timeout.toNanos();
        synchronized (lock) {
            while (getMembers().size() < count) {
                long left = deadline - System.nanoTime();
                if (left <= 0) {
                    return false;
                }
                TimeUnit.NANOSECONDS.timedWait(lock, left);
            }
            return true;
        }
    }

    /** Returns a snapshot of this member's counters. */
    public DtronStats getStats() {
        return counters.snapshot(transport.drops());
    }

    /**
     * Leaves the bus. Messages received before are still delivered to the
     * listeners (waiting a few seconds at most); closing twice does nothing.
     */
    @Override
    public void close() {
        synchronized (lock) {
            if (closed) {
                return;
            }
            closed = true;
            lock.notifyAll();
        }
        runClock.close();
        clockSync.close();
        allGroups.ifPresent(Subscription::close);
        ownGroups.forEach(Subscription::close);
        viewSubscription.close();
        transport.close();
        if (!dispatcher.shutdown(CLOSE_TIMEOUT) && !dispatcher.inExecutorThread()) {
            LOG.warn("Listeners of {} still busy {} after closing", getMemberId(), CLOSE_TIMEOUT);
        }
        synchronized (lock) {
            registrations.values().forEach(r -> r.listeners().forEach(l -> l.detach(this)));
            registrations.clear();
            membershipListeners.clear();
            servedListeners.clear();
        }
        LOG.info("Left bus '{}' as {}: {}", clusterName, getMemberId(), getStats());
    }

    @Override
    public String toString() {
        return "Dtron[" + clusterName + ", " + getMemberId() + (closed ? ", closed]" : "]");
    }

    private void requireOpen() {
        if (closed) {
            throw new IllegalStateException("Dtron closed");
        }
    }

    private static DtronChannel requireDeclared(Map<String, DtronChannel> declaredChannels, String name) {
        DtronChannel channel = declaredChannels.get(name);
        if (channel == null) {
            throw new IllegalArgumentException("channel '" + name + "' is not declared");
        }
        return channel;
    }

    /** Publishes a message of a model channel, or RUN_START or RUN_STOP; event time 0 is the publish time. */
    private IDtronChannelValued publish(IDtronChannelValued message, long eventTimeNanos) {
        return publish(message, eventTimeNanos, "", 0, 0);
    }

    /**
     * Publishes a message, with {@code text} on a channel that carries one ("" on others), the announced end of
     * the run on a run start (0 on others) and the due time of an input sent ahead (0 on others).
     */
    private IDtronChannelValued publish(IDtronChannelValued message, long eventTimeNanos, String text,
            long endTimeNanos, long dueTimeNanos) {
        Objects.requireNonNull(message, "message");
        requireOpen();
        if (dispatcher.runsInline()) {
            throw new IllegalStateException("a listener called on the bus's receiving thread may not send (see"
                    + " DtronListener.onReceivingThread): send from another thread");
        }
        String name = message.getChannelName();
        Registration registration = registrations.get(name);
        DtronChannel template = RESERVED.containsKey(name)
                ? RESERVED.get(name)
                : declared.isPresent()
                        ? declared.get().get(name)
                        : registration == null ? null : registration.template();
        if (name.equals(ACK.getChannelName()) || CONTROL.contains(name)) {
            throw new IllegalArgumentException("only DTRON publishes on channel '" + name + "'"
                    + (name.equals(ACK.getChannelName()) ? "; use acknowledge" : ""));
        }
        if (template == null && declared.isPresent()) {
            throw new InvalidMessageException(Reason.UNKNOWN_CHANNEL, "channel '" + name + "' is not declared");
        }
        if (template != null) {
            template.checkVariables(message.getVariables().keySet());
        }
        if (!RESERVED.containsKey(name)) {
            handshake.sending(List.of(name));
        }
        long now = currentTimeNanos();
        Stamp stamp = stamp(now, eventTimeNanos == 0 ? now : eventTimeNanos, "", 0);
        byte[] bytes = SyncCodec.encode(name, message.getVariables(), stamp, text, endTimeNanos, dueTimeNanos);
        try {
            transport.publish(name, bytes);
        } catch (IOException e) {
            throw new DtronException("cannot publish " + message, e);
        }
        counters.published();
        return DtronChannelValued.published(template != null ? template : DtronChannel.copyOf(message.getChannel()),
                message.getVariables(), stamp, text, endTimeNanos, dueTimeNanos);
    }

    /** Stamps a message this member publishes now, with the next sequence number. */
    private Stamp stamp(long publishTimeNanos, long eventTimeNanos, String ackedSender, long ackedSequence) {
        return stamp(sequence.incrementAndGet(), publishTimeNanos, eventTimeNanos, ackedSender, ackedSequence);
    }

    private Stamp stamp(long seq, long publishTimeNanos, long eventTimeNanos, String ackedSender,
            long ackedSequence) {
        // the tester's offset is 0 by definition; a member without an estimate sends none (0, 0)
        Optional<ClockOffset> estimate = clockSync.estimate();
        long offset = estimate.map(ClockOffset::offsetNanos).orElse(0L);
        long error = estimate.map(ClockOffset::errorNanos).orElse(0L);
        return new Stamp(getMemberId(), seq, publishTimeNanos, eventTimeNanos, getRunId(), ackedSender,
                ackedSequence, offset, error);
    }

    /** Publishes an acknowledgement unless this member acknowledged the message before. */
    private boolean publishAck(IDtronChannelValued message, long appliedAtNanos) {
        if (!claimAck(message)) {
            return false;
        }
        publishClaimedAck(message, appliedAtNanos);
        return true;
    }

    /**
     * Whether the calling thread, a listener's, leaves the publication of its acknowledgements to the listeners' thread
     * after the listener returned: on the bus's receiving thread ({@link DtronListener#onReceivingThread}) sending
     * could wait for this very thread, and on the run clock's thread handing over an input sent ahead ({@link
     * #deliverWhenDue}) it would hold up the system's timed outputs.
     */
    private boolean acknowledgesAfterListener() {
        return dispatcher.runsInline() || deferredAcks.get() != null;
    }

    /** Publishes a claimed acknowledgement by the listeners' thread, right after the listener that made it. */
    private void acknowledgeAfterListener(IDtronChannelValued message, long appliedAtNanos) {
        Runnable ack = () -> acknowledgeClaimed(message, appliedAtNanos);
        List<Runnable> deferred = deferredAcks.get();
        if (deferred != null) {
            deferred.add(ack); // published when the run clock's thread is done (see deliverWhenDue)
        } else {
            // before any message received meanwhile is delivered
            dispatcher.continueOnOwnThread(ack);
        }
    }

    /** Notes that this member acknowledges a message; false if it did before. */
    private boolean claimAck(IDtronChannelValued message) {
        synchronized (acknowledged) {
            return acknowledged.putIfAbsent(new AckKey(message.getSender(), message.getSequence()), Boolean.TRUE)
                    == null;
        }
    }

    /** Publishes the acknowledgement of a claimed message; on failure the claim is withdrawn. */
    private void publishClaimedAck(IDtronChannelValued message, long appliedAtNanos) {
        AckKey key = new AckKey(message.getSender(), message.getSequence());
        byte[] bytes = SyncCodec.encode(ACK.getChannelName(), Map.of(),
                stamp(currentTimeNanos(), appliedAtNanos, message.getSender(), message.getSequence()));
        try {
            transport.publish(ACK.getChannelName(), bytes);
        } catch (IOException | RuntimeException e) {
            synchronized (acknowledged) {
                acknowledged.remove(key);
            }
            if (e instanceof IOException) {
                throw new DtronException("cannot acknowledge " + message, e);
            }
            throw (RuntimeException) e;
        }
    }

    /** Publishes the acknowledgement of a claimed message, logging a failure (there is no caller to tell). */
    private void acknowledgeClaimed(IDtronChannelValued message, long appliedAtNanos) {
        try {
            publishClaimedAck(message, appliedAtNanos);
        } catch (DtronException | IllegalStateException e) {
            if (closed) {
                LOG.debug("{} closed before acknowledging {}", getMemberId(), message);
            } else {
                LOG.warn("{} cannot acknowledge {}: {}", getMemberId(), message, e.getMessage());
            }
        }
    }

    /** Publishes a message of the clock-offset protocol; not counted. Called on the clock's or a probing thread. */
    private void publishControl(String channel, long seq, long publishTimeNanos, long eventTimeNanos,
            String ackedSender, long ackedSequence, boolean asInput, boolean probe) {
        if (closed) {
            return;
        }
        try {
            transport.publish(channel, SyncCodec.encodeControl(channel,
                    stamp(seq, publishTimeNanos, eventTimeNanos, ackedSender, ackedSequence), asInput, probe,
                    hostClock, channel.equals(ClockSync.PONG) && getMemberId().equals(runTester) ? runEndNanos : 0));
        } catch (IOException | RuntimeException e) {
            LOG.debug("{} cannot publish on {}: {}", getMemberId(), channel, e.toString());
        }
    }

    /** Publishes this member's part of the channel-serving handshake; not counted. Called on the dispatcher. */
    private void publishServed(ServedChannels served) {
        if (closed) {
            return;
        }
        long now = currentTimeNanos();
        try {
            transport.publish(ChannelHandshake.SERVE, SyncCodec.encodeServed(ChannelHandshake.SERVE,
                    stamp(now, now, "", 0), served.receives(), served.sends(), served.joinsRun(), served.tester()));
        } catch (IOException | RuntimeException e) {
            LOG.debug("{} cannot publish the channels it serves: {}", getMemberId(), e.toString());
        }
    }

    /**
     * Called on the transport's thread, in the bus's order, when another member's announcement arrived or a member
     * that had made one left: wakes the waiters and queues the news for the served-channels listeners.
     */
    private void othersServedChanged() {
        synchronized (lock) {
            lock.notifyAll();
        }
        if (!servedListeners.isEmpty()) {
            Map<String, ServedChannels> served = handshake.others();
            dispatcher.execute(() -> servedChanged(served));
        }
    }

    /** Called on the dispatcher thread, in the bus's order. */
    private void servedChanged(Map<String, ServedChannels> served) {
        for (java.util.function.Consumer<Map<String, ServedChannels>> listener : servedListeners) {
            try {
                listener.accept(served);
            } catch (VirtualMachineError e) {
                throw e;
            } catch (Throwable e) {
                counters.listenerFailed();
                LOG.error("Served-channels listener {} failed on {}", listener, served, e);
            }
        }
    }

    private long runClockOffset() {
        // no lambda: the run clock's thread first reads this at time 0 of a fresh process's first run, and a lambda's
        // first call there costs milliseconds
        Optional<ClockOffset> estimate = clockSync.estimate();
        return estimate.isPresent() ? estimate.get().offsetNanos() : 0;
    }

    private void offsetChanged() {
        runClock.offsetChanged();
    }

    /** Called on the transport's thread: checks the message and hands it to the listeners ({@link #dispatch}). */
    private void received(BusMessage message) {
        if (closed) {
            return;
        }
        String group = message.group();
        long receiveTime = message.receiveTimeNanos() + clockShiftNanos;
        if (CONTROL.contains(group)) {
            controlReceived(message, receiveTime);
            return;
        }
        Registration registration = registrations.get(group);
        DtronChannel template = RESERVED.containsKey(group)
                ? RESERVED.get(group)
                : declared.isPresent()
                        ? declared.get().get(group)
                        : registration == null ? null : registration.template();
        if (template == null) {
            if (declared.isPresent() && servedByAnotherTester(group)) {
                recordOtherTestersMessage(message, receiveTime);
            } else if (declared.isPresent()) {
                reject(message, new InvalidMessageException(Reason.UNKNOWN_CHANNEL,
                        "channel '" + group + "' is not declared"));
            }
            return;
        }
        DtronChannelValued value;
        try {
            value = SyncCodec.decode(template, SyncCodec.parse(message.payload()), message.sender(), receiveTime);
        } catch (InvalidMessageException e) {
            reject(message, e);
            return;
        }
        recordDelay(value.getSender(), value.getPublishTimeNanos(), value.getClockOffsetNanos(),
                value.getClockErrorNanos(), receiveTime);
        if (!recordListeners.isEmpty()) {
            record(group, new Stamp(value.getSender(), value.getSequence(), value.getPublishTimeNanos(),
                    value.getEventTimeNanos(), value.getRunId(), value.getAckedSender(), value.getAckedSequence(),
                    value.getClockOffsetNanos(), value.getClockErrorNanos()), receiveTime, value.getVariables());
        }
        if (group.equals(RUN_START.getChannelName())) {
            runStarted(value);
        } else if (group.equals(RUN_STOP.getChannelName())) {
            if ((ofThisRun(value) || value.getRunId().isEmpty()) && value.getSender().equals(runTester)) {
                runStopped();
            } else if (!clockSync.isTester() && !handshake.own().receives().isEmpty()) {
                // a stop of another run (one replayed from an earlier run, say) does not end an adapter's run; a
                // member that serves no channel (a monitor that joined a running system) still hears every stop
                LOG.debug("{}: ignored a stop of run '{}' from {}: this run is '{}'", getMemberId(), value.getRunId(),
                        value.getSender(), runId);
                return;
            }
        } else if (registration != null && !value.getRunId().isEmpty() && !ofThisRun(value)
                && !RESERVED.containsKey(group) && !clockSync.isTester() && handshake.own().receives().contains(group)) {
            // an input of another run (one replayed from an earlier run, say) does not reach the adapter
            LOG.debug("{}: ignored {} of run '{}': this run is '{}'", getMemberId(), value, value.getRunId(), runId);
            return;
        }
        if (group.equals(ACK.getChannelName())
                && clockSync.probeAnswered(value.getSender(), value.getAckedSender(), value.getAckedSequence())) {
            return; // the answer to a probe sent as an input (probeAsInput), not an input's acknowledgement
        }
        if ((declared.isPresent() || registration != null) && !group.equals(ACK.getChannelName())) {
            counters.accepted();
        }
        if (registration != null) {
            // decided here, in the bus's order: an input of the current run's tester is acknowledged
            boolean acknowledge = !RESERVED.containsKey(group) && value.getSequence() > 0
                    && (value.getSender().equals(runTester) || isJoiningTester(value.getSender()))
                    && !value.getSender().equals(getMemberId());
            dispatch(value, acknowledge);
        }
    }

    /**
     * Hands a message to the listeners, in the bus's order; an input (or a probe sent as one) to be acknowledged
     * when they return. Called on the transport's thread: when every listener of the channel may be called there
     * ({@link DtronListener#onReceivingThread}; a probe has none) and nothing is queued for the listeners or being
     * delivered, they are called at once on this thread, else the message is queued for the listeners' thread. An
     * input its tester sent ahead ({@link IDtronChannelValued#getDueTimeNanos()}) is handed to them by the run clock's
     * thread when it is due, the listeners' thread waiting meanwhile.
     */
    private void dispatch(IDtronChannelValued value, boolean acknowledge) {
        Runnable delivery = () -> deliver(value, acknowledge);
        long due = acknowledge ? value.getDueTimeNanos() : 0;
        if (due > 0 || value.getChannel() == WARM_UP) {
            // an input its tester sent ahead: delivered by the run clock when it is due, what follows behind it (the
            // warm-up message, due at once, takes this way too, so that a run's first such input does not pay for it)
            dispatcher.execute(() -> deliverWhenDue(due + value.getClockOffsetNanos(), delivery));
        } else if (mayRunOnReceivingThread(value)) {
            dispatcher.runOrExecute(delivery);
        } else {
            dispatcher.execute(delivery);
        }
    }

    /**
     * Called on the listeners' thread: hands a message to the listeners from the run clock's thread at {@code
     * dueEpochNanos} ({@link RunClock#runAt}) and then publishes the acknowledgements made meanwhile, here: a
     * publication may wait for the bus for milliseconds, and the run clock's thread runs the system's timed outputs.
     */
    private void deliverWhenDue(long dueEpochNanos, Runnable delivery) {
        List<Runnable> acks = new ArrayList<>(1);
        runClock.runAt(dueEpochNanos, () -> {
            deferredAcks.set(acks);
            try {
                delivery.run();
            } finally {
                deferredAcks.remove();
            }
        });
        acks.forEach(Runnable::run);
    }

    /** Whether all listeners of a message's channel may be called on the receiving thread (a probe has none). */
    private boolean mayRunOnReceivingThread(IDtronChannelValued value) {
        if (value.getChannelName().equals(ClockSync.PING)) {
            return true;
        }
        Registration registration = registrations.get(value.getChannelName());
        return registration != null && onReceivingThread.containsAll(registration.listeners());
    }

    private static boolean asksReceivingThread(DtronListener listener) {
        try {
            return listener.onReceivingThread();
        } catch (RuntimeException e) {
            LOG.warn("Listener {} failed to tell whether it may be called on the receiving thread: {}", listener,
                    e.toString());
            return false;
        }
    }

    /**
     * Whether another tester on the bus (one that announced itself, or said in the handshake that it joins a run)
     * serves {@code channel}: a channel of its model, which a tester of the same run sees pass without it being
     * one of its own.
     */
    private boolean servedByAnotherTester(String channel) {
        Set<String> testers = clockSync.otherTesters();
        for (ServedChannels served : handshake.others().values()) {
            if ((served.joinsRun() || served.tester() || testers.contains(served.member()))
                    && (served.receives().contains(channel) || served.sends().contains(channel))) {
                return true;
            }
        }
        return false;
    }

    /**
     * A message on another tester's channel: not this member's to check or count, only to hand to the record
     * listeners, so that a tester's trace holds the whole run. One that is no valid {@code Sync} is rejected.
     */
    private void recordOtherTestersMessage(BusMessage message, long receiveTime) {
        if (recordListeners.isEmpty()) {
            return;
        }
        Sync sync = parseOrReject(message);
        if (sync == null) {
            return;
        }
        Map<String, Integer> variables = new LinkedHashMap<>();
        sync.getVariablesList().forEach(v -> variables.putIfAbsent(v.getName(), v.getValue()));
        record(message.group(), SyncCodec.stamp(sync, message.sender()), receiveTime, variables);
    }

    /** The message's {@code Sync}, or null when it is none: then it is rejected (logged and counted). */
    private Sync parseOrReject(BusMessage message) {
        try {
            return SyncCodec.parse(message.payload());
        } catch (InvalidMessageException e) {
            reject(message, e);
            return null;
        }
    }

    /** A hello, ping, pong or serve: for the clock offset and the handshake, not for listeners. */
    private void controlReceived(BusMessage message, long receiveTime) {
        Sync sync = parseOrReject(message);
        if (sync == null) {
            return;
        }
        Stamp stamp = SyncCodec.stamp(sync, message.sender());
        recordDelay(stamp, receiveTime);
        record(message.group(), stamp, receiveTime, Map.of());
        switch (message.group()) {
            case ClockSync.HELLO -> {
                if (!stamp.sender().equals(getMemberId())) {
                    testersSeen.add(stamp.sender());
                    clockSync.testerAnnounced(stamp.sender(), false);
                }
                handshake.helloReceived();
            }
            case ChannelHandshake.SERVE -> {
                if (sync.getTester()) {
                    testersSeen.add(stamp.sender());
                }
                if (sync.getHoldsInputs()) {
                    holdingMembers.add(stamp.sender());
                } else {
                    holdingMembers.remove(stamp.sender());
                }
                handshake.servedReceived(new ServedChannels(stamp.sender(), Set.copyOf(sync.getReceivesList()),
                        Set.copyOf(sync.getSendsList()), sync.getJoinsRun(), sync.getTester()));
            }
            case ClockSync.PING -> {
                boolean peerTester = isJoiningTester(stamp.sender());
                if (sync.getAsInput() && !clockSync.isTester() && stamp.sequence() > 0
                        && clockSync.answersPingOf(stamp.sender(), peerTester)) {
                    // the tester warms this member's path of an input up: answered as an input is, heard by no one
                    try {
                        dispatch(SyncCodec.decode(RESERVED.get(ClockSync.PING), sync, message.sender(), receiveTime),
                                true);
                    } catch (InvalidMessageException e) {
                        reject(message, e);
                    }
                } else {
                    clockSync.pingReceived(stamp.sender(), stamp.sequence(), receiveTime, peerTester,
                            sync.getProbe());
                }
            }
            case ClockSync.PONG -> {
                if (stamp.ackedSender().equals(getMemberId())) {
                    announcedEnd = new TesterSide.AnnouncedEnd(stamp.runId(), sync.getEndTimeNs());
                }
                clockSync.pongReceived(stamp.sender(), stamp.ackedSender(), stamp.ackedSequence(),
                        stamp.effectiveEventTimeNanos(), receiveTime, sync.getHostClock());
            }
            default -> throw new IllegalStateException("not a control channel: " + message.group());
        }
    }

    /** Hands a received message to the record listeners. */
    private void record(String channel, Stamp stamp, long receiveTime, Map<String, Integer> variables) {
        if (recordListeners.isEmpty()) {
            return;
        }
        BusRecord record = new BusRecord(channel, stamp.sender(), stamp.sequence(), stamp.publishTimeNanos(),
                stamp.effectiveEventTimeNanos(), receiveTime, stamp.runId(), stamp.ackedSender(),
                stamp.ackedSequence(), stamp.clockOffsetNanos(), stamp.clockErrorNanos(), variables);
        for (java.util.function.Consumer<BusRecord> listener : recordListeners) {
            try {
                listener.accept(record);
            } catch (RuntimeException e) {
                LOG.warn("Record listener {} failed on a message of {}: {}", listener, stamp.sender(), e.toString());
            }
        }
    }

    /** Whether a member said it is a tester that takes part in a run another one starts. */
    private boolean isJoiningTester(String member) {
        return handshake.joinsRun(member);
    }

    private void recordDelay(Stamp stamp, long receiveTime) {
        recordDelay(stamp.sender(), stamp.publishTimeNanos(), stamp.clockOffsetNanos(), stamp.clockErrorNanos(),
                receiveTime);
    }

    /**
     * Counts the delay of a message on the tester's clock: from a member that sent its clock offset estimate, or from
     * the tester itself, when this member is the tester or has an estimate of its own.
     */
    private void recordDelay(String sender, long publishTime, long offset, long error, long receiveTime) {
        if (publishTime == 0 || sender.equals(getMemberId())) {
            return;
        }
        Optional<ClockOffset> own = clockSync.estimate();
        if (own.isEmpty() || error <= 0 && !own.get().tester().equals(sender)) {
            return;
        }
        long delay = receiveTime + own.get().offsetNanos() - (publishTime + offset);
        long bound = error + own.get().errorNanos();
        delays.merge(sender, MemberDelay.first(sender, delay, bound), (old, one) -> old.plus(delay, bound));
    }

    /** Whether a message carries the id of the run this member takes part in (none: false). */
    private boolean ofThisRun(IDtronChannelValued message) {
        return !runId.isEmpty() && message.getRunId().equals(runId);
    }

    /** Called on the transport's thread, in the bus's order. */
    private void runStarted(IDtronChannelValued start) {
        runTester = start.getSender();
        if (runTester.equals(getMemberId())) {
            handshake.testing();
        } else {
            testersSeen.add(runTester);
        }
        runId = start.getRunId();
        runEndNanos = start.getEndTimeNanos();
        clockSync.testerAnnounced(start.getSender(), true);
        runClock.start(start.getEventTimeNanos(), start.getVariables().get("timeunit"), start.getRunId());
    }

    /** Called on the transport's thread, in the bus's order. */
    private void runStopped() {
        runTester = null;
        runEndNanos = 0;
        runId = "";
        runClock.stop();
    }

    private void reject(BusMessage message, InvalidMessageException reason) {
        counters.rejected(reason.getReason());
        LOG.warn("Rejected a message on channel '{}' from {} ({} bytes), {}: {}", message.group(), message.sender(),
                message.payloadLength(), reason.getReason(), reason.getMessage());
    }

    /**
     * Called on the dispatcher thread, or inline on the transport's thread (see {@link #dispatch}), in the bus's
     * order; acknowledges the message after its listeners. A probe sent as an input ({@link TesterSide#probeAsInput})
     * takes the same way, but no listener hears it.
     */
    private void deliver(IDtronChannelValued value, boolean acknowledge) {
        boolean probe = value.getChannelName().equals(ClockSync.PING);
        Registration registration = value.getChannel() == WARM_UP ? null : registrations.get(value.getChannelName());
        if (registration == null && !probe) {
            return;
        }
        boolean inline = dispatcher.runsInline();
        if (inline && !probe && !onReceivingThread.containsAll(registration.listeners())) {
            // a listener that may not run here was added since dispatch: the listeners' thread delivers, in this place
            dispatcher.continueOnOwnThread(() -> deliver(value, acknowledge));
            return;
        }
        boolean called = probe;
        boolean automatic = true;
        for (DtronListener listener : probe ? List.<DtronListener>of() : registration.listeners()) {
            called = true;
            try {
                listener.messageReceived(value);
            } catch (VirtualMachineError e) {
                throw e;
            } catch (Throwable e) {
                counters.listenerFailed();
                LOG.error("Listener {} failed on message {}", listener, value, e);
            }
            automatic &= autoAcknowledges(listener);
        }
        if (acknowledge && called && automatic) {
            long appliedAt = currentTimeNanos();
            if (!claimAck(value)) {
                return;
            }
            if (acknowledgesAfterListener()) {
                acknowledgeAfterListener(value, appliedAt);
            } else {
                acknowledgeClaimed(value, appliedAt);
            }
        }
    }

    private static boolean autoAcknowledges(DtronListener listener) {
        try {
            return listener.autoAcknowledge();
        } catch (RuntimeException e) {
            LOG.warn("Listener {} failed to tell whether to acknowledge: {}", listener, e.toString());
            return true;
        }
    }

    /** Called on the transport's thread, one view at a time. */
    private void viewChanged(MembershipView view) {
        LOG.info("Bus '{}' members: {}", clusterName, view.members());
        List<String> joined = view.joinedSince(lastView);
        List<String> left = view.leftSince(lastView);
        lastView = view;
        String tester = runTester;
        if (tester != null && left.contains(tester)) {
            LOG.info("The run's tester {} left the bus; the run clock stops", tester);
            runStopped();
        }
        clockSync.viewChanged(view.members(), !joined.isEmpty());
        handshake.viewChanged(view.members());
        synchronized (lock) {
            lock.notifyAll();
        }
        if (!joined.isEmpty() || !left.isEmpty()) {
            dispatcher.execute(() -> membershipChanged(view.members(), joined, left));
        }
    }

    /** Called on the dispatcher thread, in the bus's order. */
    private void membershipChanged(List<String> members, List<String> joined, List<String> left) {
        for (DtronMembershipListener listener : membershipListeners) {
            try {
                listener.membershipChanged(members, joined, left);
            } catch (VirtualMachineError e) {
                throw e;
            } catch (Throwable e) {
                counters.listenerFailed();
                LOG.error("Membership listener {} failed on members {} (joined {}, left {})", listener, members,
                        joined, left, e);
            }
        }
    }
}
