package io.dtron.api.internal;

import io.dtron.api.ClockOffset;
import io.dtron.api.internal.OffsetEstimator.Estimate;
import java.time.Duration;
import java.util.Collection;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;
import java.util.function.LongSupplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. One member's side of the clock-offset protocol.
 *
 * <p>The tester (a member connected with the tester option, or one that sent the last run start) publishes a hello
 * when it joins and after members joined, and answers every ping with a pong that names the ping and carries, as
 * event time, its clock when the ping arrived. Every other member learns the tester from its hello or run start,
 * pings it a few times at once and then about once a second while it is on the bus, and keeps an
 * {@link OffsetEstimator estimate} of (tester's clock - own clock). Messages are published on a thread of its own;
 * the receive methods are called on the transport's thread. Thread-safe.
 */
public final class ClockSync implements AutoCloseable {
    /** The channel of the tester's hello. */
    public static final String HELLO = "dtron_hello";
    /** The channel of a member's ping to the tester. */
    public static final String PING = "dtron_ping";
    /** The channel of the tester's answer to a ping. */
    public static final String PONG = "dtron_pong";

    private static final Logger LOG = LoggerFactory.getLogger(ClockSync.class);
    private static final int BURST = OffsetEstimator.WINDOW;
    private static final long BURST_SPACING_MILLIS = 20;
    private static final long PING_PERIOD_MILLIS = 1_000;
    private static final long[] HELLO_DELAYS_MILLIS = {100, 1_000};
    private static final int MAX_PENDING_PINGS = 64;

    /** Publishes one control message; must not throw. */
    @FunctionalInterface
    public interface ControlPublisher {
        /**
         * Publishes a message without variables.
         *
         * @param channel          {@link #HELLO}, {@link #PING} or {@link #PONG}
         * @param sequence         its sequence number
         * @param publishTimeNanos the own clock now
         * @param eventTimeNanos   its event time
         * @param ackedSender      on a pong the ping's sender, else ""
         * @param ackedSequence    on a pong the ping's sequence number, else 0
         * @param asInput          on a ping of a {@link #probe}: whether the members are asked to answer it as they
         *                         acknowledge an input (field {@code as_input} of {@code Sync}), else false
         * @param probe            on a ping of a {@link #probe} but as an input: true, every member answers it whoever
         *                         sent it (field {@code probe} of {@code Sync}); false on a clock sample's ping
         */
        void publish(String channel, long sequence, long publishTimeNanos, long eventTimeNanos, String ackedSender,
                long ackedSequence, boolean asInput, boolean probe);
    }

    /**
     * How far a tester's clock reading may lie outside a ping's round trip while the two clocks are still taken as
     * one (the clocks' resolution is a microsecond).
     */
    static final long SAME_CLOCK_SLACK_NANOS = 1_000;

    private final String me;
    private final String hostClock;
    private final boolean announced;
    private final LongSupplier clock;
    private final LongSupplier nextSequence;
    private final ControlPublisher publisher;
    private final Runnable estimateChanged;
    private final ScheduledExecutorService executor;
    private final OffsetEstimator estimator = new OffsetEstimator();
    private final Map<Long, Long> pendingPings = new LinkedHashMap<>() {
        @Override
        protected boolean removeEldestEntry(Map.Entry<Long, Long> eldest) {
            return size() > MAX_PENDING_PINGS;
        }
    };
    private String tester;
    private boolean selfTester;
    /**
     * Whether the tester said it reads this member's very clock ({@link HostClock}) and no round trip has
     * contradicted it: the offset is then 0 within the clock's resolution.
     */
    private boolean sameClock;
    /** Whether a round trip contradicted the tester's claim to read this member's clock. */
    private boolean sameClockRefuted;
    /** The members other than this one that announced themselves as the tester, while they are on the bus. */
    private final Set<String> otherTesters = new LinkedHashSet<>();
    /** The members that answered each of this member's probes, by the probe's sequence number. */
    private final Map<Long, Set<String>> probes = new ConcurrentHashMap<>();
    private long pingGeneration;
    private ScheduledFuture<?> pinging;
    private volatile Optional<ClockOffset> estimate = Optional.empty();
    private volatile boolean closed;

    /**
     * Creates the member's side; {@link #start} begins it.
     *
     * @param me              this member's id
     * @param hostClock       the id of the wall clock {@code clock} reads ({@link HostClock#id()}), or "" when it
     *                        is not that clock alone (shifted for a test)
     * @param tester          whether this member is the tester from the start (and says so with hellos)
     * @param clock           this member's wall clock, ns since the epoch
     * @param nextSequence    hands out this member's sequence numbers
     * @param publisher       publishes control messages
     * @param estimateChanged called (on any thread, without locks held) when {@link #estimate()} changed
     */
    public ClockSync(String me, String hostClock, boolean tester, LongSupplier clock, LongSupplier nextSequence,
            ControlPublisher publisher, Runnable estimateChanged) {
        this.me = me;
        this.hostClock = hostClock;
        this.announced = tester;
        this.clock = clock;
        this.nextSequence = nextSequence;
        this.publisher = publisher;
        this.estimateChanged = estimateChanged;
        this.executor = Executors.newSingleThreadScheduledExecutor(task -> {
            Thread thread = new Thread(task, "dtron-clock-" + me);
            thread.setDaemon(true);
            return thread;
        });
    }

    /** Starts: a tester announces itself. */
    public void start() {
        if (announced) {
            synchronized (this) {
                selfTester = true;
                tester = me;
                estimate = Optional.of(new ClockOffset(me, 0, 0));
            }
            submit(this::hello);
            scheduleHellos();
        }
    }

    /** Returns whether this member is the tester now. */
    public synchronized boolean isTester() {
        return selfTester;
    }

    /**
     * Returns the members other than this one that announced themselves as the tester (by a hello or a run start)
     * and are still on the bus: for a tester, testers of other runs on the same bus.
     */
    public synchronized Set<String> otherTesters() {
        return Set.copyOf(otherTesters);
    }

    /** Returns the tester this member knows of, itself included. */
    public synchronized Optional<String> tester() {
        return Optional.ofNullable(tester);
    }

    /** Returns the estimate of (tester's clock - own clock): exact 0 on the tester, empty when there is none. */
    public Optional<ClockOffset> estimate() {
        return estimate;
    }

    /**
     * Called when a member announced itself as the tester, by a hello or a run start. A hello does not take a member
     * away from the tester it knows (another tester's hello is another run's); a run start does.
     */
    public void testerAnnounced(String member, boolean byRunStart) {
        synchronized (this) {
            if (closed) {
                return;
            }
            if (member.equals(me)) {
                if (selfTester) {
                    return;
                }
                selfTester = true;
                tester = me;
                stopPinging();
                forgetSamples();
                estimate = Optional.of(new ClockOffset(me, 0, 0));
                LOG.debug("{} is the tester now", me);
            } else {
                otherTesters.add(member);
                if (announced) {
                    LOG.debug("Member {} announced itself as the tester, but {} is; ignored", member, me);
                    return;
                }
                if (member.equals(tester) || !byRunStart && tester != null && !selfTester) {
                    return;
                }
                selfTester = false;
                tester = member;
                forgetSamples();
                estimate = Optional.empty();
                startPinging();
                LOG.debug("{} learned the tester {}; estimating the clock offset", me, member);
            }
        }
        estimateChanged.run();
    }

    /** Called with every membership view: forgets a tester that left; a tester greets members that joined. */
    public void viewChanged(List<String> members, boolean someoneJoined) {
        boolean forgot = false;
        boolean greet;
        synchronized (this) {
            if (closed) {
                return;
            }
            otherTesters.retainAll(members);
            if (tester != null && !selfTester && !members.contains(tester)) {
                LOG.debug("{}: the tester {} left; no clock offset any more", me, tester);
                tester = null;
                stopPinging();
                forgetSamples();
                estimate = Optional.empty();
                forgot = true;
            }
            greet = selfTester && someoneJoined;
        }
        if (greet) {
            scheduleHellos();
        }
        if (forgot) {
            estimateChanged.run();
        }
    }

    /**
     * Called when a ping arrived: the tester answers it with its clock at {@code receiveTimeNanos}, and a member
     * answers the ping (a {@link #probe}) of its tester, or of another tester of the run ({@code fromPeerTester}),
     * the same way, and a {@code probe} of any other member (a live monitor's) too.
     */
    public void pingReceived(String from, long sequence, long receiveTimeNanos, boolean fromPeerTester,
            boolean probe) {
        if (!answersPingOf(from, fromPeerTester) && !(probe && !from.equals(me))) {
            return;
        }
        submit(() -> publisher.publish(PONG, nextSequence.getAsLong(), clock.getAsLong(), receiveTimeNanos, from,
                sequence, false, false));
    }

    /**
     * Returns whether this member answers a ping of {@code from}: the tester answers every other member's, a member
     * its tester's and those of another tester of the run ({@code fromPeerTester}).
     */
    public synchronized boolean answersPingOf(String from, boolean fromPeerTester) {
        return !from.equals(me) && (selfTester || from.equals(tester) || fromPeerTester);
    }

    /**
     * Called when a pong arrived: one of this member's pings answered by its tester gives a sample. A tester whose
     * {@code testerHostClock} is this member's own reads the same clock: the offset is 0, give or take the clock's
     * resolution, as long as every round trip agrees (the tester's reading lies within it); else the estimate is the
     * round trips'.
     */
    public void pongReceived(String from, String ackedSender, long ackedSequence, long testerTimeNanos,
            long receiveTimeNanos, String testerHostClock) {
        if (!ackedSender.equals(me) || probeAnswered(from, ackedSender, ackedSequence)) {
            return;
        }
        Optional<ClockOffset> before;
        Optional<ClockOffset> after;
        synchronized (this) {
            if (closed || selfTester || !from.equals(tester)) {
                return;
            }
            Long sentAt = pendingPings.remove(ackedSequence);
            if (sentAt == null) {
                return;
            }
            before = estimate;
            Optional<Estimate> sampled = estimator.add(sentAt, testerTimeNanos, receiveTimeNanos);
            boolean within = testerTimeNanos >= sentAt - SAME_CLOCK_SLACK_NANOS
                    && testerTimeNanos <= receiveTimeNanos + SAME_CLOCK_SLACK_NANOS;
            if (!within && sameClock) {
                LOG.warn("The tester {} said it reads this member's clock, but a round trip contradicts it ({} ns"
                        + " outside); the clock offset is estimated from round trips", from,
                        testerTimeNanos < sentAt ? sentAt - testerTimeNanos : testerTimeNanos - receiveTimeNanos);
            }
            sameClockRefuted |= !within;
            sameClock = within && !sameClockRefuted && !hostClock.isEmpty() && hostClock.equals(testerHostClock);
            after = sameClock ? Optional.of(new ClockOffset(from, 0, SAME_CLOCK_SLACK_NANOS))
                    : sampled.map(e -> new ClockOffset(from, e.offsetNanos(), e.errorNanos()));
            estimate = after;
        }
        if (!after.equals(before)) {
            if (before.isEmpty()) {
                after.ifPresent(e -> LOG.info("Clock offset to the tester {}: {} ms +/- {} ms", from,
                        millis(e.offsetNanos()), millis(e.errorNanos())));
            } else {
                after.ifPresent(e -> LOG.debug("Clock offset to the tester {}: {} ms +/- {} ms", from,
                        millis(e.offsetNanos()), millis(e.errorNanos())));
            }
            estimateChanged.run();
        }
    }

    /**
     * Called when a pong or an acknowledgement arrived: whether it answers one of this member's {@linkplain #probe
     * probes} (which then counts {@code from} as answered).
     */
    public boolean probeAnswered(String from, String ackedSender, long ackedSequence) {
        if (!ackedSender.equals(me)) {
            return false;
        }
        Set<String> answered = probes.get(ackedSequence);
        if (answered == null) {
            return false;
        }
        synchronized (answered) {
            answered.add(from);
            answered.notifyAll();
        }
        return true;
    }

    /**
     * Pings every member and waits until each of {@code expected} answered, or the timeout passed: the ping is marked
     * {@code probe}, which every member answers whoever this member is (a tester, a live monitor). Messages are
     * delivered in each member's order, so an answer also means that everything the member sent before it has
     * arrived. With {@code asInput} the ping asks the members to answer it as they acknowledge an input (see {@link
     * #probeAnswered}), and is not marked: only the members whose tester this member is, or that take it for another
     * tester of their run, answer it; a member that does not know how answers with a pong, which counts as well.
     *
     * @return the members that answered
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public Set<String> probe(Collection<String> expected, Duration timeout, boolean asInput)
            throws InterruptedException {
        long sequence = nextSequence.getAsLong();
        long now = clock.getAsLong();
        Set<String> answered = new LinkedHashSet<>();
        probes.put(sequence, answered);
        try {
            publisher.publish(PING, sequence, now, now, "", 0, asInput, !asInput);
            long deadline = System.nanoTime() + timeout.toNanos();
            synchronized (answered) {
                while (!answered.containsAll(expected)) {
                    long left = deadline - System.nanoTime();
                    if (left <= 0) {
                        break;
                    }
                    TimeUnit.NANOSECONDS.timedWait(answered, left);
                }
                return Set.copyOf(answered);
            }
        } finally {
            probes.remove(sequence);
        }
    }

    /** Called with the lock held: forgets the samples of a tester, and whether it reads this member's clock. */
    private void forgetSamples() {
        estimator.clear();
        sameClock = false;
        sameClockRefuted = false;
    }

    /** Stops pinging and greeting; closing twice does nothing. */
    @Override
    public void close() {
        synchronized (this) {
            closed = true;
            stopPinging();
        }
        executor.shutdownNow();
    }

    private static String millis(long nanos) {
        return String.format(java.util.Locale.ROOT, "%.3f", nanos / 1e6);
    }

    /** Called with the lock held. */
    private void startPinging() {
        stopPinging();
        long generation = pingGeneration;
        pinging = schedule(() -> ping(generation, 0), 0);
    }

    /** Called with the lock held. */
    private void stopPinging() {
        pingGeneration++;
        if (pinging != null) {
            pinging.cancel(false);
            pinging = null;
        }
        pendingPings.clear();
    }

    private void ping(long generation, int count) {
        long sequence;
        long sentAt;
        synchronized (this) {
            if (closed || generation != pingGeneration) {
                return;
            }
            sequence = nextSequence.getAsLong();
            sentAt = clock.getAsLong();
            pendingPings.put(sequence, sentAt);
            pinging = schedule(() -> ping(generation, count + 1),
                    count + 1 < BURST ? BURST_SPACING_MILLIS : PING_PERIOD_MILLIS);
        }
        publisher.publish(PING, sequence, sentAt, sentAt, "", 0, false, false);
    }

    private void hello() {
        if (isTester()) {
            long now = clock.getAsLong();
            publisher.publish(HELLO, nextSequence.getAsLong(), now, now, "", 0, false, false);
        }
    }

    private void scheduleHellos() {
        for (long delay : HELLO_DELAYS_MILLIS) {
            schedule(this::hello, delay);
        }
    }

    private void submit(Runnable task) {
        schedule(task, 0);
    }

    private ScheduledFuture<?> schedule(Runnable task, long delayMillis) {
        try {
            return executor.schedule(() -> {
                try {
                    task.run();
                } catch (RuntimeException e) {
                    LOG.warn("Clock offset task of {} failed: {}", me, e.toString());
                }
            }, delayMillis, TimeUnit.MILLISECONDS);
        } catch (RejectedExecutionException e) {
            return null; // closed
        }
    }
}
