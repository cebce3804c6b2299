package io.dtron.bus.internal;

import io.nats.client.Connection;
import io.nats.client.Consumer;
import io.nats.client.Dispatcher;
import io.nats.client.ErrorListener;
import io.nats.client.JetStream;
import io.nats.client.JetStreamApiException;
import io.nats.client.JetStreamManagement;
import io.nats.client.JetStreamSubscription;
import io.nats.client.Message;
import io.nats.client.Nats;
import io.nats.client.Options;
import io.nats.client.PushSubscribeOptions;
import io.nats.client.api.ConsumerConfiguration;
import io.nats.client.api.DeliverPolicy;
import io.nats.client.api.DiscardPolicy;
import io.nats.client.api.MessageInfo;
import io.nats.client.api.StorageType;
import io.nats.client.api.StreamConfiguration;
import io.nats.client.api.StreamState;
import io.nats.client.impl.Headers;
import io.nats.client.impl.NatsMessage;
import java.io.IOException;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.security.GeneralSecurityException;
import java.security.KeyStore;
import java.security.SecureRandom;
import java.security.cert.Certificate;
import java.security.cert.CertificateFactory;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.EnumMap;
import java.util.HashMap;
import java.util.HashSet;
import java.util.HexFormat;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;
import javax.net.ssl.SSLContext;
import javax.net.ssl.TrustManagerFactory;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. A {@link Transport} on NATS JetStream: one stream per bus ({@link NatsSettings#streamName()}) takes every
 * message of every member, and every member delivers the stream from an ordered consumer, so that all members, in
 * any language, see one order: the stream's.
 *
 * <p>A channel message goes to subject {@code dtron.BUS.c.GROUP} with header {@value #SENDER} naming its member.
 * Membership travels in the same stream, on subject {@code dtron.BUS.p}, with header {@value #PRESENCE}: a member
 * says {@code join} when it connects, {@code alive} every {@link NatsSettings#HEARTBEAT} and at once when another
 * member joins (with {@value #JOINED}, the stream sequence of its own join, so that newcomers order the members as
 * the others do), and {@code leave} when it closes. Every member applies the same rule at every stream message, in
 * stream order, so all compute the same views: a member whose last message in the stream is more than
 * {@link NatsSettings#SILENCE} older (by the stream's timestamps) than the message at hand has left; a presence
 * message of a member not in the view adds it. A view's id is the stream sequence of the message that changed it.
 *
 * <p>On a secure bus ({@link NatsSettings#macKey()}) every message carries {@value MessageCodes#SEQ}, {@value
 * MessageCodes#TIME} and {@value MessageCodes#MAC} (security.md), and a received message without a valid code, or
 * replayed, or stale, is dropped before membership and delivery see it, and counted in {@link #drops()}. A member
 * joining a secure bus first reads the stream's messages of the 240 s before its join for their senders' counters
 * only, so that a copy of one of them published again after it joined is replayed for it too. On an insecure bus
 * messages carry no code, and one that carries a code (a secure member's) is dropped.
 */
public final class NatsTransport implements Transport {
    /** Header naming the member that published a message. */
    public static final String SENDER = "Dtron-Sender";
    /** Header of a presence message: join, alive or leave. */
    public static final String PRESENCE = "Dtron-Presence";
    /** Header of an alive message: the stream sequence at which its member joined. */
    public static final String JOINED = "Dtron-Joined";

    private static final Logger LOG = LoggerFactory.getLogger(NatsTransport.class);
    private static final long CONNECT_TIMEOUT_MILLIS = 10_000;
    /** How long a message the stream did not acknowledge is tried again before it is dropped. */
    private static final Duration RETRY_FOR = Duration.ofSeconds(30);
    private static final long RETRY_PAUSE_MILLIS = 100;
    private static final long CLOSE_WAIT_MILLIS = 3_000;
    /** The API error of a stream that holds no message of a sequence. */
    private static final int NO_MESSAGE_FOUND = 10037;
    /** How many (sender, reason) pairs of dropped messages are logged, one line each, before logging stops. */
    private static final int DROPS_LOGGED = 256;
    /**
     * How far back a member joining a secure bus reads the stream before its join, by the stream's timestamps: a
     * copy of a message is accepted only within 120 s of the time its sender put in it, which is within 120 s of when
     * the stream stored the message first.
     */
    private static final Duration HISTORY = Duration.ofNanos(2 * MessageCodes.Check.MAX_SKEW_NANOS);

    private final Connection connection;
    private final NatsSettings settings;
    private final JetStream jetStream;
    private final String channelPrefix;
    private final Subscribers subscribers = new Subscribers();
    private final ScheduledExecutorService presence;
    private final Object sendLock = new Object();
    /** The source of the messages' {@code Nats-Msg-Id}s. */
    private final SecureRandom msgIds = new SecureRandom();
    private final AtomicInteger inFlight = new AtomicInteger();
    private final ExecutorService retries;
    /**
     * This member's message counter, {@value MessageCodes#SEQ}: its first message has the wall clock at its start
     * (ns), each further one the next number, so that a member of the same name started later has higher numbers.
     */
    private final AtomicLong published = new AtomicLong(EpochClock.nowNanos() - 1);
    /** The codes of the bus's secret; null on an insecure bus. */
    private final MessageCodes codes;
    /** The check of received messages on a secure bus, on the receive thread only; null on an insecure one. */
    private final MessageCodes.Check check;
    private final Map<DropReason, LongAdder> drops = new EnumMap<>(DropReason.class);
    /** The (sender, reason) pairs of dropped messages logged so far, on the receive thread only. */
    private final Set<String> dropsLogged = new HashSet<>();
    /** Why this member dropped its own message last, if it did: a join that does not come back says why. */
    private volatile DropReason ownDropped;
    /** The {@value MessageCodes#SEQ} of this member's join, its first message. */
    private final String joinSeq;
    /**
     * On a secure bus, until this member's join came back: the stream's messages before it are read only for their
     * senders' counters (security.md), so that a copy of one of them published again after the join is replayed.
     */
    private volatile boolean learning;
    private final CountDownLatch joined = new CountDownLatch(1);
    /** Membership state, touched on the receive thread only: last stream time (ns) and join sequence per member. */
    private final Map<String, Long> lastSeen = new HashMap<>();
    private final Map<String, Long> joinedAt = new HashMap<>();
    private volatile long ownJoin;
    private volatile MembershipView view;
    private volatile boolean closed;
    private volatile boolean leaving;
    private Dispatcher dispatcher;
    private volatile JetStreamSubscription subscription;
    /** The stream sequence of the last message delivered, and when (System.nanoTime) a message last came. */
    private volatile long lastSequence;
    private volatile long lastDeliveredNanos = System.nanoTime();
    /** A gap was seen and its consumer is being made anew: later messages wait for it, and are not reported. */
    private final AtomicBoolean gapReported = new AtomicBoolean();
    /**
     * The first message of a consumer made anew is taken whatever its sequence: the server starts from the first
     * message it still holds.
     */
    private volatile boolean acceptAnySequence;

    private NatsTransport(Connection connection, NatsSettings settings) throws IOException {
        this.connection = connection;
        this.settings = settings;
        this.jetStream = connection.jetStream();
        this.channelPrefix = "dtron." + settings.busName() + ".c.";
        this.view = new MembershipView(0, List.of(settings.memberName()));
        this.codes = settings.macKey().map(MessageCodes::forKey).orElse(null);
        this.check = codes == null ? null : codes.check();
        this.joinSeq = Long.toString(published.get() + 1);
        this.learning = check != null;
        for (DropReason reason : DropReason.values()) {
            drops.put(reason, new LongAdder());
        }
        this.presence = Executors.newSingleThreadScheduledExecutor(task -> {
            Thread thread = new Thread(task, "dtron-nats-presence-" + settings.memberName());
            thread.setDaemon(true);
            return thread;
        });
        this.retries = Executors.newSingleThreadExecutor(task -> {
            Thread thread = new Thread(task, "dtron-nats-retry-" + settings.memberName());
            thread.setDaemon(true);
            return thread;
        });
    }

    /**
     * Connects to the servers, creates the bus's stream unless it exists, and joins the bus.
     *
     * @throws IOException          if no server can be reached, the servers refuse the credentials, JetStream is
     *                              off, or this member's join does not come back within 10 s
     * @throws InterruptedException if the thread was interrupted while connecting
     */
    public static NatsTransport connect(NatsSettings settings) throws IOException, InterruptedException {
        Connection connection;
        try {
            connection = Nats.connect(options(settings));
        } catch (GeneralSecurityException e) {
            throw new IOException("cannot set up TLS with " + settings.tlsCaFile().orElseThrow() + ": "
                    + e.getMessage(), e);
        }
        NatsTransport transport = null;
        try {
            ensureStream(connection, settings);
            transport = new NatsTransport(connection, settings);
            transport.join();
        } catch (IOException | InterruptedException | RuntimeException | Error e) {
            if (transport != null) {
                transport.presence.shutdownNow();
                transport.retries.shutdownNow();
            }
            connection.close();
            throw e;
        }
        LOG.debug("Joined {}: {}", settings, transport.view);
        return transport;
    }

    private static Options options(NatsSettings settings) throws IOException, GeneralSecurityException {
        Options.Builder builder = new Options.Builder()
                .servers(settings.servers().toArray(String[]::new))
                .connectionName(settings.memberName())
                .maxReconnects(-1)
                .errorListener(new LoggingErrorListener(settings.memberName()));
        if (settings.user().isPresent()) {
            builder.userInfo(settings.user().get(), settings.password().orElseThrow());
        }
        settings.token().ifPresent(builder::token);
        if (settings.credentialsFile().isPresent() || settings.nkeyFile().isPresent()) {
            requireNkeySigning();
        }
        if (settings.credentialsFile().isPresent()) {
            builder.authHandler(Nats.credentials(settings.credentialsFile().get().toString()));
        }
        if (settings.nkeyFile().isPresent()) {
            char[] seed = Files.readString(settings.nkeyFile().get(), StandardCharsets.US_ASCII).trim().toCharArray();
            builder.authHandler(Nats.staticCredentials(null, seed));
        }
        if (settings.tlsCaFile().isPresent()) {
            builder.sslContext(trusting(settings.tlsCaFile().get()));
        }
        return builder.build();
    }

    /** Nkeys are signed with Bouncy Castle, which DTRON does not bring along (see the root pom). */
    private static void requireNkeySigning() throws IOException {
        try {
            Class.forName("org.bouncycastle.crypto.signers.Ed25519Signer", false, NatsTransport.class.getClassLoader());
        } catch (ClassNotFoundException e) {
            throw new IOException("nkey and credentials-file authentication need Bouncy Castle on the classpath"
                    + " (org.bouncycastle:bcprov-lts8on)", e);
        }
    }

    /** An SSL context that trusts the certificates of a PEM file. */
    private static SSLContext trusting(java.nio.file.Path caFile) throws IOException, GeneralSecurityException {
        KeyStore store = KeyStore.getInstance(KeyStore.getDefaultType());
        store.load(null, null);
        try (InputStream in = Files.newInputStream(caFile)) {
            int i = 0;
            for (Certificate certificate : CertificateFactory.getInstance("X.509").generateCertificates(in)) {
                store.setCertificateEntry("ca" + i++, certificate);
            }
            if (i == 0) {
                throw new IOException("no certificate in " + caFile);
            }
        }
        TrustManagerFactory trust = TrustManagerFactory.getInstance(TrustManagerFactory.getDefaultAlgorithm());
        trust.init(store);
        SSLContext context = SSLContext.getInstance("TLS");
        context.init(null, trust.getTrustManagers(), null);
        return context;
    }

    /**
     * Creates the bus's stream unless it exists (created by another member, maybe with other limits); waits up to
     * the connect timeout while JetStream is unavailable (a cluster electing its leader).
     */
    private static void ensureStream(Connection connection, NatsSettings settings)
            throws IOException, InterruptedException {
        JetStreamManagement management = connection.jetStreamManagement();
        long deadline = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(CONNECT_TIMEOUT_MILLIS);
        while (true) {
            try {
                ensureStream(management, settings);
                return;
            } catch (JetStreamApiException e) {
                if (e.getErrorCode() != 503 || System.nanoTime() > deadline) {
                    throw new IOException("JetStream refused stream " + settings.streamName() + ": " + e.getMessage(),
                            e);
                }
                Thread.sleep(RETRY_PAUSE_MILLIS);
            }
        }
    }

    private static void ensureStream(JetStreamManagement management, NatsSettings settings)
            throws IOException, JetStreamApiException {
        try {
            management.getStreamInfo(settings.streamName());
            return;
        } catch (JetStreamApiException e) {
            if (e.getErrorCode() != 404) {
                throw e;
            }
        }
        StreamConfiguration config = StreamConfiguration.builder()
                .name(settings.streamName())
                .subjects(settings.streamSubjects())
                .storageType(StorageType.File)
                .replicas(settings.replicas())
                .maxAge(NatsSettings.MAX_AGE)
                .maxBytes(NatsSettings.MAX_BYTES)
                .discardPolicy(DiscardPolicy.Old)
                .duplicateWindow(NatsSettings.DUPLICATE_WINDOW)
                .build();
        try {
            management.addStream(config);
            LOG.info("Created stream {} for bus '{}'", settings.streamName(), settings.busName());
        } catch (JetStreamApiException e) {
            if (e.getErrorCode() == 503) {
                throw e;
            }
            management.getStreamInfo(settings.streamName()); // another member created it meanwhile, or this throws
        }
    }

    /**
     * Subscribes from the stream's next message on (on a secure bus: from {@link #HISTORY} before its last one),
     * says join and waits until the join came back, for as long as the stream's messages before it keep coming.
     */
    private void join() throws IOException, InterruptedException {
        dispatcher = connection.createDispatcher();
        try {
            subscription = subscribe(learning ? history() : ConsumerConfiguration.builder()
                    .deliverPolicy(DeliverPolicy.New));
        } catch (JetStreamApiException e) {
            throw new IOException("JetStream refused a consumer on stream " + settings.streamName() + ": "
                    + e.getMessage(), e);
        }
        publishPresence("join");
        while (!joined.await(CONNECT_TIMEOUT_MILLIS, TimeUnit.MILLISECONDS)) {
            DropReason dropped = ownDropped;
            if (learning && dropped == null && System.nanoTime() - lastDeliveredNanos < TimeUnit.MILLISECONDS
                    .toNanos(CONNECT_TIMEOUT_MILLIS)) {
                continue; // still reading the messages before the join
            }
            throw new IOException("this member's join did not come back from stream " + settings.streamName()
                    + " within " + CONNECT_TIMEOUT_MILLIS + " ms" + (learning
                            ? " of the last earlier message the stream delivered (or of connecting, if none came)" : "")
                    + (dropped == null ? ""
                    : "; it dropped its own messages as " + dropped.name().toLowerCase(java.util.Locale.ROOT)
                    + (dropped == DropReason.STALE ? " (this machine's clock is more than 120 s from the NATS"
                            + " server's)" : "")));
        }
        long period = NatsSettings.HEARTBEAT.toMillis();
        presence.scheduleAtFixedRate(() -> {
            presenceQuietly("alive");
            resubscribeIfStalled();
        }, period, period, TimeUnit.MILLISECONDS);
    }

    /**
     * Where a member joining a secure bus starts reading: at the stream's messages of the last {@link #HISTORY}
     * before its last message (the stream's clock, whatever this machine's), or at the first when it holds none.
     */
    private ConsumerConfiguration.Builder history() throws IOException, JetStreamApiException {
        StreamState state = connection.jetStreamManagement().getStreamInfo(settings.streamName()).getStreamState();
        ConsumerConfiguration.Builder consumer = ConsumerConfiguration.builder();
        if (state.getMsgCount() == 0 || state.getLastTime() == null) {
            return consumer.deliverPolicy(DeliverPolicy.All);
        }
        return consumer.deliverPolicy(DeliverPolicy.ByStartTime).startTime(state.getLastTime().minus(HISTORY));
    }

    /**
     * An ordered consumer of the stream on the dispatcher, with heartbeats every second: a consumer whose server
     * died is noticed and made anew by the client (from the next stream sequence) within a few seconds instead of
     * the default's fifteen.
     */
    private JetStreamSubscription subscribe(ConsumerConfiguration.Builder consumer)
            throws IOException, JetStreamApiException {
        return jetStream.subscribe(settings.streamSubjects(), dispatcher, this::received, false,
                PushSubscribeOptions.builder().ordered(true).configuration(consumer.idleHeartbeat(Duration.ofSeconds(1))
                        .build()).build());
    }

    /**
     * This member's own heartbeat comes back from the stream every second: when nothing at all came for {@link
     * NatsSettings#STALL}, the consumer is stuck (its server died during a leader election, and the client did not
     * make it anew), and it is made anew here, from the sequence after the last delivered.
     */
    private void resubscribeIfStalled() {
        long silentNanos = System.nanoTime() - lastDeliveredNanos;
        if (silentNanos >= NatsSettings.STALL.toNanos()) {
            resubscribe("nothing for " + silentNanos / 1_000_000 + " ms, this member's heartbeats included");
        }
    }

    /**
     * Makes the consumer anew from the sequence after the last delivered (on the presence thread, one at a time);
     * when it cannot yet (no server, no stream leader), the next heartbeat's check tries again.
     */
    private void resubscribe(String why) {
        if (closed || leaving || connection.getStatus() != Connection.Status.CONNECTED) {
            gapReported.set(false);
            return;
        }
        long from = lastSequence + 1;
        if (cannotBeDelivered(from)) {
            lastSequence = from;
            from++;
        }
        JetStreamSubscription stuck = subscription;
        if (stuck != null) {
            // first: the old consumer must deliver nothing after the new one's first messages
            subscription = null;
            try {
                dispatcher.unsubscribe(stuck);
            } catch (RuntimeException e) {
                LOG.debug("{} cannot unsubscribe its old consumer: {}", settings.memberName(), e.toString());
            }
        }
        try {
            acceptAnySequence = true;
            subscription = subscribe(ConsumerConfiguration.builder().deliverPolicy(DeliverPolicy.ByStartSequence)
                    .startSequence(from));
            lastDeliveredNanos = System.nanoTime();
            LOG.warn("{}: consumer of stream {} made anew from sequence {} ({})", settings.memberName(),
                    settings.streamName(), from, why);
        } catch (IOException | JetStreamApiException | RuntimeException e) {
            LOG.debug("{} cannot make its consumer anew yet: {}", settings.memberName(), e.toString());
        } finally {
            gapReported.set(false);
        }
    }

    /**
     * Whether the stream's message {@code sequence}, from which a consumer made anew delivered nothing, is one no
     * member would take: gone, or without a valid code on a bus with a secret (a client without it can publish a
     * message whose headers read as a server's status, which the client library keeps from the consumer's handler,
     * so that the consumer waits for it for ever). It is counted as an unauthenticated message then, and the
     * consumer is made from the one after it; a message a member would take is waited for, as before.
     */
    private boolean cannotBeDelivered(long sequence) {
        MessageInfo info;
        try {
            JetStreamManagement management = connection.jetStreamManagement();
            if (sequence > management.getStreamInfo(settings.streamName()).getStreamState().getLastSequence()) {
                return false; // not stored yet: the consumer waits for the stream's next message
            }
            info = management.getMessage(settings.streamName(), sequence);
        } catch (JetStreamApiException e) {
            if (e.getApiErrorCode() == NO_MESSAGE_FOUND) {
                LOG.warn("{}: stream {} holds no sequence {}, from which its consumer was to be made anew: skipped",
                        settings.memberName(), settings.streamName(), sequence);
                return true;
            }
            LOG.debug("{} cannot read sequence {} of stream {}: {}", settings.memberName(), sequence,
                    settings.streamName(), e.toString());
            return false;
        } catch (IOException | RuntimeException e) {
            LOG.debug("{} cannot read sequence {} of stream {}: {}", settings.memberName(), sequence,
                    settings.streamName(), e.toString());
            return false;
        }
        Headers headers = info.getHeaders();
        if (codes == null || headers != null && codes.matches(headers.getFirst(MessageCodes.MAC), info.getSubject(),
                headers.getFirst(SENDER), headers.getFirst(MessageCodes.SEQ), headers.getFirst(MessageCodes.TIME),
                headers.getFirst(PRESENCE), headers.getFirst(JOINED), info.getData())) {
            return false; // a member's message: it is the consumer that is stuck
        }
        dropped(DropReason.UNAUTHENTICATED, headers == null ? null : headers.getFirst(SENDER), info.getSubject());
        return true;
    }

    @Override
    public String localMember() {
        return settings.memberName();
    }

    @Override
    public void publish(String group, byte[] payload) throws IOException {
        Objects.requireNonNull(group, "group");
        Objects.requireNonNull(payload, "payload");
        if (closed) {
            throw new IllegalStateException("transport closed");
        }
        if (group.isEmpty() || !group.chars().allMatch(c -> c > 0x20 && c < 0x7F && c != '.' && c != '*'
                && c != '>')) {
            throw new IllegalArgumentException("group '" + group + "' cannot be a NATS subject token");
        }
        Headers headers = new Headers().put(SENDER, settings.memberName());
        send(settings.channelSubject(group), headers, payload);
    }

    /**
     * Hands a message to the connection, which sends the messages in the order they were handed over, and does not
     * wait for the stream's acknowledgement. A message the stream did not acknowledge (a server failing over) is
     * published again by the retry thread, with the same {@code Nats-Msg-Id}, so that the stream stores it once;
     * while a server fails over, a message published again may come after later ones of the same member. On a secure
     * bus the message is signed here, once: a message published again keeps its number, time and code, within the
     * retries' 30 s well inside the 120 s a receiver allows, and a copy the stream stored twice is dropped as
     * replayed.
     */
    private void send(String subject, Headers headers, byte[] payload) throws IOException {
        synchronized (sendLock) { // the ids and the connection's order agree
            String seq = Long.toString(published.incrementAndGet());
            headers.put("Nats-Msg-Id", settings.memberName() + "-" + msgId());
            if (codes != null) {
                String time = Long.toString(EpochClock.nowNanos());
                headers.put(MessageCodes.SEQ, seq).put(MessageCodes.TIME, time);
                headers.put(MessageCodes.MAC, codes.code(subject, headers.getFirst(SENDER), seq, time,
                        headers.getFirst(PRESENCE), headers.getFirst(JOINED), payload));
            }
            Message message = NatsMessage.builder().subject(subject).headers(headers).data(payload).build();
            try {
                inFlight.incrementAndGet();
                jetStream.publishAsync(message).whenComplete((ack, failure) -> {
                    if (failure == null) {
                        inFlight.decrementAndGet();
                    } else {
                        retryLater(message, failure);
                    }
                });
            } catch (IllegalStateException e) {
                inFlight.decrementAndGet();
                throw new IOException("cannot publish on " + subject + ": " + e.getMessage(), e);
            }
        }
    }

    /**
     * 32 random hexadecimal digits: an id no one can tell in advance, so that no other process can publish first
     * under it and have the stream drop this member's message as the duplicate.
     */
    private String msgId() {
        byte[] id = new byte[16];
        msgIds.nextBytes(id);
        return HexFormat.of().formatHex(id);
    }

    private void retryLater(Message message, Throwable failure) {
        LOG.debug("{}: the stream did not acknowledge a message on {}, again: {}", settings.memberName(),
                message.getSubject(), failure.toString());
        try {
            retries.execute(() -> {
                try {
                    publishUntilStored(message);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                } finally {
                    inFlight.decrementAndGet();
                }
            });
        } catch (RejectedExecutionException e) {
            inFlight.decrementAndGet(); // closed
        }
    }

    private void publishUntilStored(Message message) throws InterruptedException {
        long deadline = System.nanoTime() + RETRY_FOR.toNanos();
        while (true) {
            try {
                jetStream.publish(NatsMessage.builder().subject(message.getSubject()).headers(message.getHeaders())
                        .data(message.getData()).build());
                return;
            } catch (JetStreamApiException e) {
                if (e.getErrorCode() != 503) { // the stream refused it for good (limits, a bad subject)
                    LOG.warn("{}: stream {} refused a message on {}: {}", settings.memberName(),
                            settings.streamName(), message.getSubject(), e.getMessage());
                    return;
                }
                LOG.debug("{}: JetStream unavailable for a moment: {}", settings.memberName(), e.getMessage());
            } catch (IOException | RuntimeException e) {
                LOG.debug("{}: publishing on {} failed, again: {}", settings.memberName(), message.getSubject(),
                        e.toString());
            }
            if (System.nanoTime() > deadline || connection.getStatus() == Connection.Status.CLOSED) {
                LOG.warn("{}: a message on {} was not stored within {}; dropped", settings.memberName(),
                        message.getSubject(), RETRY_FOR);
                return;
            }
            Thread.sleep(RETRY_PAUSE_MILLIS);
        }
    }

    private void publishPresence(String what) throws IOException {
        Headers headers = new Headers().put(SENDER, settings.memberName()).put(PRESENCE, what);
        long joinedSequence = ownJoin;
        if (what.equals("alive") && joinedSequence > 0) {
            headers.put(JOINED, Long.toString(joinedSequence));
        }
        send(settings.presenceSubject(), headers, new byte[0]);
    }

    private void presenceQuietly(String what) {
        if (closed) {
            return;
        }
        try {
            publishPresence(what);
        } catch (IOException | RuntimeException e) {
            LOG.debug("{} cannot say {}: {}", settings.memberName(), what, e.toString());
        }
    }

    private void presenceSoon(String what) {
        try {
            presence.execute(() -> presenceQuietly(what));
        } catch (RejectedExecutionException e) {
            // closed
        }
    }

    @Override
    public Subscription subscribe(String group, java.util.function.Consumer<BusMessage> handler) {
        return subscribers.subscribe(group, handler);
    }

    @Override
    public Subscription subscribeAll(java.util.function.Consumer<BusMessage> handler) {
        return subscribers.subscribeAll(handler);
    }

    @Override
    public MembershipView view() {
        return view;
    }

    @Override
    public Subscription addViewListener(java.util.function.Consumer<MembershipView> listener) {
        return subscribers.addViewListener(listener);
    }

    @Override
    public void close() {
        if (closed) {
            return;
        }
        presence.shutdownNow();
        leaving = true;
        try {
            publishPresence("leave");
        } catch (IOException | RuntimeException e) {
            LOG.debug("{} cannot say leave: {}", settings.memberName(), e.toString());
        }
        // the messages handed over before, and the leave, are stored first
        long deadline = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(CLOSE_WAIT_MILLIS);
        try {
            while (inFlight.get() > 0 && System.nanoTime() < deadline) {
                Thread.sleep(5);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        retries.shutdownNow();
        closed = true;
        try {
            if (dispatcher != null && subscription != null) {
                dispatcher.unsubscribe(subscription);
            }
        } catch (RuntimeException e) {
            LOG.debug("{} cannot unsubscribe: {}", settings.memberName(), e.toString());
        }
        try {
            connection.close();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /** Called on the dispatcher's thread, one stream message at a time in stream order. */
    private void received(Message message) {
        long receivedAt = EpochClock.nowNanos();
        if (closed || !message.isJetStream()) {
            return;
        }
        long sequence = message.metaData().streamSequence();
        if (sequence <= lastSequence) {
            return; // delivered already, by a consumer this one replaced
        }
        if (sequence > lastSequence + 1 && lastSequence > 0 && !acceptAnySequence) {
            // every message of the stream is this consumer's: a gap is a message the client skipped (it happens
            // to ordered consumers when a server fails over); the consumer is made anew from the missing one
            if (gapReported.compareAndSet(false, true)) {
                LOG.warn("{}: stream {} delivered sequence {} after {}; its consumer is made anew from {}",
                        settings.memberName(), settings.streamName(), sequence, lastSequence, lastSequence + 1);
                presence.execute(() -> resubscribe("a gap in the stream's sequence"));
            }
            return;
        }
        if (sequence > lastSequence + 1 && lastSequence > 0) {
            LOG.warn("{}: stream {} no longer holds sequences {} to {} (older than its limits keep)",
                    settings.memberName(), settings.streamName(), lastSequence + 1, sequence - 1);
        }
        acceptAnySequence = false;
        lastSequence = sequence;
        lastDeliveredNanos = System.nanoTime();
        Instant stamp = message.metaData().timestamp().toInstant();
        long streamTime = stamp.getEpochSecond() * 1_000_000_000L + stamp.getNano();
        Headers headers = message.getHeaders();
        String sender = headers == null ? null : headers.getFirst(SENDER);
        String subject = message.getSubject();
        if (learning && (headers == null || !settings.memberName().equals(sender)
                || !joinSeq.equals(headers.getFirst(MessageCodes.SEQ)))) {
            if (headers != null) { // published before this member joined: only its counter is of interest
                check.learn(subject, sender, headers.getFirst(MessageCodes.SEQ), headers.getFirst(MessageCodes.TIME),
                        headers.getFirst(PRESENCE), headers.getFirst(JOINED), message.getData(),
                        headers.getFirst(MessageCodes.MAC));
            }
            return;
        }
        DropReason drop = screen(subject, headers, message.getData(), streamTime);
        if (drop != null) {
            dropped(drop, sender, subject);
            return;
        }
        learning = false;
        boolean presenceMessage = subject.equals(settings.presenceSubject());
        try {
            membership(sequence, streamTime, sender, presenceMessage ? headers : null);
        } catch (RuntimeException e) {
            LOG.error("Membership update failed on {}", subject, e);
        }
        if (presenceMessage) {
            return;
        }
        if (!subject.startsWith(channelPrefix) || subject.length() == channelPrefix.length()) {
            LOG.debug("Ignored a message on subject {} of stream {}", subject, settings.streamName());
            return;
        }
        String group = subject.substring(channelPrefix.length());
        if (!subscribers.wants(group)) {
            return;
        }
        byte[] data = message.getData();
        subscribers.deliver(new BusMessage(group, data == null ? new byte[0] : data, sender == null ? "" : sender,
                receivedAt));
    }

    /** Why a received message is dropped (security.md), or null when it passes. */
    private DropReason screen(String subject, Headers headers, byte[] data, long streamTime) {
        String mac = headers == null ? null : headers.getFirst(MessageCodes.MAC);
        if (check == null) {
            return mac == null ? null : DropReason.UNAUTHENTICATED;
        }
        if (headers == null) {
            return DropReason.UNAUTHENTICATED;
        }
        return check.check(subject, headers.getFirst(SENDER), headers.getFirst(MessageCodes.SEQ),
                headers.getFirst(MessageCodes.TIME), headers.getFirst(PRESENCE), headers.getFirst(JOINED), data, mac,
                streamTime);
    }

    /** Counts a dropped message; the first of each reason from each sender is logged, in one line. */
    private void dropped(DropReason reason, String sender, String subject) {
        drops.get(reason).increment();
        if (settings.memberName().equals(sender)) {
            ownDropped = reason;
        }
        String who = sender == null ? "a sender without " + SENDER : printable(sender);
        if (dropsLogged.size() > DROPS_LOGGED || !dropsLogged.add(reason + " " + who)) {
            return;
        }
        String why = switch (reason) {
            case UNAUTHENTICATED -> check == null
                    ? "it carries a code of a secret and this member is insecure (--insecure)"
                    : "it carries no valid code of the bus's secret";
            case REPLAYED -> "its " + MessageCodes.SEQ + " was accepted already (a message published again)";
            case STALE -> "its " + MessageCodes.TIME + " is more than 120 s from when the stream stored it";
        };
        LOG.warn("{}: dropped a message on {} from {}, {}: {}; more such are counted, not logged",
                settings.memberName(), printable(subject), who, reason.name().toLowerCase(java.util.Locale.ROOT), why);
        if (dropsLogged.size() > DROPS_LOGGED) {
            LOG.warn("{}: dropped messages of more than {} senders and reasons; no more are logged, all are"
                    + " counted", settings.memberName(), DROPS_LOGGED);
        }
    }

    /** A header or subject fit for one log line: printable ASCII, at most 128 characters. */
    private static String printable(String text) {
        StringBuilder out = new StringBuilder();
        text.codePoints().limit(128).forEach(c -> out.append(c >= 0x20 && c < 0x7F ? (char) c : '?'));
        return text.length() > 128 ? out + "..." : out.toString();
    }

    /** How many received messages this member dropped (security.md), by reason. */
    @Override
    public Map<DropReason, Long> drops() {
        Map<DropReason, Long> counts = new EnumMap<>(DropReason.class);
        drops.forEach((reason, count) -> counts.put(reason, count.sum()));
        return counts;
    }

    /**
     * Applies the membership rule at one stream message: members silent for longer than the silence are gone, a
     * presence message adds its member or (leave) removes it, any message of a member counts as a sign of life.
     */
    private void membership(long sequence, long streamTime, String sender, Headers presenceHeaders) {
        List<String> before = view.members();
        List<String> members = new ArrayList<>(before);
        long silence = NatsSettings.SILENCE.toNanos();
        members.removeIf(member -> lastSeen.containsKey(member) && lastSeen.get(member) < streamTime - silence);
        String me = settings.memberName();
        if (sender != null && (members.contains(sender) || presenceHeaders != null)) {
            lastSeen.put(sender, streamTime);
        }
        if (presenceHeaders != null && sender != null) {
            String what = Objects.requireNonNullElse(presenceHeaders.getFirst(PRESENCE), "");
            switch (what) {
                case "join", "alive" -> {
                    long joinedSequence = what.equals("join") ? sequence : parseOr(presenceHeaders.getFirst(JOINED),
                            sequence);
                    if (!members.contains(sender)) {
                        members.add(sender);
                        joinedAt.put(sender, joinedSequence);
                    } else if (what.equals("join")) {
                        joinedAt.put(sender, joinedSequence);
                    }
                    if (what.equals("join") && sender.equals(me)) {
                        ownJoin = sequence;
                        joined.countDown();
                    } else if (what.equals("join")) {
                        presenceSoon("alive"); // tell the newcomer who is here
                    }
                }
                case "leave" -> {
                    members.remove(sender);
                    lastSeen.remove(sender);
                }
                default -> LOG.debug("Ignored presence '{}' of {}", what, sender);
            }
        }
        if (!members.contains(me) && before.contains(me) && joined.getCount() == 0 && !leaving) {
            LOG.warn("{} was silent in stream {} for longer than {}; joining again", me, settings.streamName(),
                    NatsSettings.SILENCE);
            presenceSoon("join");
        }
        lastSeen.keySet().retainAll(members);
        joinedAt.keySet().retainAll(members);
        members.sort(Comparator.comparingLong((String m) -> joinedAt.getOrDefault(m, Long.MAX_VALUE))
                .thenComparing(Comparator.naturalOrder()));
        if (!members.equals(before)) {
            MembershipView previous = view;
            MembershipView next = new MembershipView(sequence, members);
            view = next;
            LOG.debug("{}: view {} (joined {}, left {})", me, next, next.joinedSince(previous),
                    next.leftSince(previous));
            subscribers.viewChanged(next);
        }
    }

    private static long parseOr(String value, long fallback) {
        if (value == null) {
            return fallback;
        }
        try {
            return Long.parseLong(value.trim());
        } catch (NumberFormatException e) {
            return fallback;
        }
    }

    /** Logs what the NATS client reports through slf4j. */
    private record LoggingErrorListener(String member) implements ErrorListener {
        @Override
        public void errorOccurred(Connection conn, String error) {
            LOG.warn("{}: NATS server error: {}", member, error);
        }

        @Override
        public void exceptionOccurred(Connection conn, Exception exp) {
            LOG.debug("{}: NATS client exception: {}", member, exp.toString());
        }

        @Override
        public void slowConsumerDetected(Connection conn, Consumer consumer) {
            LOG.warn("{}: NATS slow consumer: messages dropped", member);
        }
    }
}
