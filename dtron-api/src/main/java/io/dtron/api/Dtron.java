package io.dtron.api;

import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.api.internal.BusConnector;
import io.dtron.api.internal.Counters;
import io.dtron.api.internal.DtronChannel;
import io.dtron.api.internal.DtronChannelValued;
import io.dtron.api.internal.SerialExecutor;
import io.dtron.api.internal.SyncCodec;
import io.dtron.bus.BusMessage;
import io.dtron.bus.MembershipView;
import io.dtron.bus.Subscription;
import io.dtron.bus.Transport;
import io.dtron.bus.internal.EpochClock;
import java.io.IOException;
import java.time.Duration;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
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
 * {@code Sync}, names an unknown channel, or carries unknown or missing
 * variables is rejected: logged with the reason, counted in
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

    private static final Logger LOG = LoggerFactory.getLogger(Dtron.class);
    private static final Duration CLOSE_TIMEOUT = Duration.ofSeconds(5);

    private final Transport transport;
    private final String clusterName;
    private final Optional<Map<String, DtronChannel>> declared;
    private final Map<String, Registration> registrations = new ConcurrentHashMap<>();
    private final List<DtronMembershipListener> membershipListeners = new CopyOnWriteArrayList<>();
    private final Counters counters = new Counters();
    private final AtomicLong sequence = new AtomicLong();
    private final SerialExecutor dispatcher;
    private final Object lock = new Object();
    private final Subscription viewSubscription;
    private final Optional<Subscription> allGroups;
    private MembershipView lastView;
    private volatile boolean closed;

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
        this.lastView = transport.view();
        this.viewSubscription = transport.addViewListener(this::viewChanged);
        this.allGroups = declared.map(d -> transport.subscribeAll(this::received));
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
     *                        members refused this member's secret
     */
    public static Dtron connect(DtronOptions options) {
        Objects.requireNonNull(options, "options");
        SyncCodec.warmUp();
        Transport transport;
        try {
            transport = BusConnector.connect(options);
        } catch (SecurityException e) {
            throw new DtronException("the members of bus '" + options.getClusterName()
                    + "' refused this member: " + e.getMessage(), e);
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
        synchronized (lock) {
            requireOpen();
            Registration registration = registrations.get(name);
            DtronChannel known = registration != null
                    ? registration.template()
                    : declared.map(d -> requireDeclared(d, name)).orElse(template);
            if (!known.isCompatible(template)) {
                throw new IllegalArgumentException("listener template " + template + " differs from " + known);
            }
            if (!listener.attach(this)) {
                throw new IllegalStateException("listener " + listener + " belongs to another Dtron");
            }
            if (registration == null) {
                Optional<Subscription> group = declared.isPresent()
                        ? Optional.empty()
                        : Optional.of(transport.subscribe(name, this::received));
                registration = new Registration(known, new CopyOnWriteArrayList<>(), group);
                registrations.put(name, registration);
            }
            if (!registration.listeners().contains(listener)) {
                registration.listeners().add(listener);
            }
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
            listener.detach(this);
            if (registration.listeners().isEmpty()) {
                registrations.remove(name);
                registration.group().ifPresent(Subscription::close);
            }
        }
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
     * Publishes a message to every member, stamped with this member's id, the
     * next sequence number and the publish time.
     *
     * @throws InvalidMessageException if the channel is not declared (when channels are declared) or its
     *                                 variables do not fit the template known here
     * @throws IllegalStateException   if this {@code Dtron} is closed
     * @throws DtronException          if the bus did not take the message
     */
    public void send(IDtronChannelValued message) {
        Objects.requireNonNull(message, "message");
        requireOpen();
        String name = message.getChannelName();
        DtronChannel template = declared.isPresent()
                ? declared.get().get(name)
                : Optional.ofNullable(registrations.get(name)).map(Registration::template).orElse(null);
        if (template == null && declared.isPresent()) {
            throw new InvalidMessageException(Reason.UNKNOWN_CHANNEL, "channel '" + name + "' is not declared");
        }
        if (template != null) {
            template.checkVariables(message.getVariables().keySet());
        }
        byte[] bytes = SyncCodec.encode(name, message.getVariables(), getMemberId(), sequence.incrementAndGet(),
                EpochClock.nowNanos());
        try {
            transport.publish(name, bytes);
        } catch (IOException e) {
            throw new DtronException("cannot publish " + message, e);
        }
        counters.published();
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
        return counters.snapshot();
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
        allGroups.ifPresent(Subscription::close);
        viewSubscription.close();
        transport.close();
        if (!dispatcher.shutdown(CLOSE_TIMEOUT) && !dispatcher.inExecutorThread()) {
            LOG.warn("Listeners of {} still busy {} after closing", getMemberId(), CLOSE_TIMEOUT);
        }
        synchronized (lock) {
            registrations.values().forEach(r -> r.listeners().forEach(l -> l.detach(this)));
            registrations.clear();
            membershipListeners.clear();
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

    /** Called on the transport's thread: checks the message and queues it for the listeners. */
    private void received(BusMessage message) {
        if (closed) {
            return;
        }
        String group = message.group();
        Registration registration = registrations.get(group);
        DtronChannel template = declared.isPresent()
                ? declared.get().get(group)
                : registration == null ? null : registration.template();
        if (template == null) {
            if (declared.isPresent()) {
                reject(message, new InvalidMessageException(Reason.UNKNOWN_CHANNEL,
                        "channel '" + group + "' is not declared"));
            }
            return;
        }
        DtronChannelValued value;
        try {
            value = SyncCodec.decode(template, SyncCodec.parse(message.payload()), message.sender(),
                    message.receiveTimeNanos());
        } catch (InvalidMessageException e) {
            reject(message, e);
            return;
        }
        counters.accepted();
        if (registration != null) {
            dispatcher.execute(() -> deliver(value));
        }
    }

    private void reject(BusMessage message, InvalidMessageException reason) {
        counters.rejected(reason.getReason());
        LOG.warn("Rejected a message on channel '{}' from {} ({} bytes), {}: {}", message.group(), message.sender(),
                message.payloadLength(), reason.getReason(), reason.getMessage());
    }

    /** Called on the dispatcher thread, in the bus's order. */
    private void deliver(IDtronChannelValued value) {
        Registration registration = registrations.get(value.getChannelName());
        if (registration == null) {
            return;
        }
        for (DtronListener listener : registration.listeners()) {
            try {
                listener.messageReceived(value);
            } catch (VirtualMachineError e) {
                throw e;
            } catch (Throwable e) {
                counters.listenerFailed();
                LOG.error("Listener {} failed on message {}", listener, value, e);
            }
        }
    }

    /** Called on the transport's thread, one view at a time. */
    private void viewChanged(MembershipView view) {
        LOG.info("Bus '{}' members: {}", clusterName, view.members());
        List<String> joined = view.joinedSince(lastView);
        List<String> left = view.leftSince(lastView);
        lastView = view;
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
