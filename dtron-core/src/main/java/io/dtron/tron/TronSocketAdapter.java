package io.dtron.tron;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.tron.internal.FrameReader;
import io.dtron.tron.internal.FrameWriter;
import io.dtron.tron.internal.InterfaceRegistry;
import io.dtron.tron.internal.Wire;
import java.io.Closeable;
import java.io.EOFException;
import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * DTRON in TRON's place: the tester's side of TRON's socket-adapter protocol, so that an adapter written against
 * TRON's Java or C API (or {@link TronAdapterClient}) is tested by DTRON's engine unchanged.
 *
 * <p>A factory ({@link #accept}, {@link #connect}, {@link #configure}) runs the configuration phase at once: the
 * adapter registers inputs, outputs and their variables, the time unit and the timeout, and starts the test; the
 * names are resolved against the model (global channels, or {@code name[i]} elements of channel arrays; global int
 * and bool variables), refusals are answered with negative error codes that command 127 explains, and a start after
 * a refusal is refused. Then {@link #testInterface()} is the interface the adapter defined, for {@link
 * io.dtron.engine.OnlineTester}'s constructor, and this object is the {@link Adapter} of the run. The start is
 * accepted when the engine starts the run, so the adapter's time 0 is the tester's.
 *
 * <p>Time:
 * <ul>
 *   <li>Real time: inputs are sent as the engine applies them; outputs are reported to the engine as they arrive,
 *       time-stamped with the arrival of their first byte. No acknowledgements.</li>
 *   <li>Virtual time, TRON's acknowledgements: after sending an input, the engine's thread waits for the adapter's
 *       acknowledgement, so virtual time does not move meanwhile; outputs that arrive before it are observed at the
 *       input's instant (the adapter's immediate reaction). Every output is acknowledged. An output the adapter
 *       sends on its own, not in answer to an input, is observed at whatever virtual time the tester has reached
 *       when it arrives, so adapters for virtual time should be reactive; a timed adapter should use real time or
 *       the shared virtual clock.</li>
 *   <li>Virtual time, TRON's virtual clock server ({@link #useClockServer}, {@code -Q PORT}): as with TRON's
 *       acknowledgements, and the adapter's threads take their time from the run's clock; the tester waits after
 *       the start, each input and each wake-up until they are all blocked again.</li>
 *   <li>Virtual time, shared virtual clock (DTRON's extension, asked for by the adapter with command 200, which
 *       TRON's own adapters never send): the adapter's timers run on the tester's virtual clock. The adapter tells
 *       its next timer's time after every turn; the tester grants time (a clock message on channel 0) when the
 *       engine's virtual time reaches that timer, or before an input, and waits until the adapter has answered.
 *       Outputs sent during a turn are observed at the turn's time. Runs are then deterministic.</li>
 * </ul>
 *
 * <p>Errors: a protocol violation during configuration (unknown command, truncated frame, the connection closed,
 * silence past the configuration timeout) is a {@link TronProtocolException} from the factory; during the test (an
 * event on a channel id never registered, an input sent by the adapter, a wrong number of values, a truncated frame,
 * a missing acknowledgement, the connection dropped) the run ends INCONCLUSIVE with the explanation, and the
 * connection is closed.
 */
public final class TronSocketAdapter implements Adapter, Closeable {
    /** How long an adapter may stay silent during configuration by default. */
    public static final Duration DEFAULT_CONFIGURATION_TIMEOUT = Duration.ofSeconds(10);
    private static final Logger LOG = LoggerFactory.getLogger(TronSocketAdapter.class);
    /**
     * The most events one acknowledgement is taken to count: a frame starting with bit 31 set and a larger count is a
     * negative channel id, not an acknowledgement.
     */
    private static final int MAX_ACK_COUNT = 0xffff;

    /**
     * How the tester side runs.
     *
     * @param virtualTime          whether the run is in virtual time (acknowledgements are exchanged)
     * @param frameTimeout         how long the rest of a frame may take once its first byte came
     * @param replyTimeout         in virtual time, how long the adapter may take to acknowledge an input or to answer
     *                             a time grant
     * @param configurationTimeout how long the adapter may stay silent during configuration (and how long
     *                             connecting may take)
     */
    public record Settings(boolean virtualTime, Duration frameTimeout, Duration replyTimeout,
                           Duration configurationTimeout) {
        public Settings {
            requirePositive(frameTimeout, "frameTimeout");
            requirePositive(replyTimeout, "replyTimeout");
            requirePositive(configurationTimeout, "configurationTimeout");
        }

        private static void requirePositive(Duration d, String name) {
            if (Objects.requireNonNull(d, name).isNegative() || d.isZero()) {
                throw new IllegalArgumentException(name + " must be positive");
            }
        }

        /**
         * Real time: frames within 5 s, configuration within {@link #DEFAULT_CONFIGURATION_TIMEOUT} (a TRON adapter
         * registers its channels as soon as it is connected; a peer that stays silent is no TRON adapter).
         */
        public static Settings forRealTime() {
            return new Settings(false, Duration.ofSeconds(5), Duration.ofSeconds(10), DEFAULT_CONFIGURATION_TIMEOUT);
        }

        /** Virtual time: as real time, and acknowledgements within 10 s. */
        public static Settings forVirtualTime() {
            return forRealTime().withVirtualTime(true);
        }

        /** These settings in virtual or real time. */
        public Settings withVirtualTime(boolean virtual) {
            return new Settings(virtual, frameTimeout, replyTimeout, configurationTimeout);
        }

        /** These settings with another frame timeout. */
        public Settings withFrameTimeout(Duration timeout) {
            return new Settings(virtualTime, timeout, replyTimeout, configurationTimeout);
        }

        /** These settings with another reply timeout. */
        public Settings withReplyTimeout(Duration timeout) {
            return new Settings(virtualTime, frameTimeout, timeout, configurationTimeout);
        }

        /** These settings with another configuration timeout. */
        public Settings withConfigurationTimeout(Duration timeout) {
            return new Settings(virtualTime, frameTimeout, replyTimeout, timeout);
        }
    }

    /** What the adapter's reader thread hands to the engine's thread in virtual time. */
    private interface Control {
    }

    private record Ack(int count) implements Control {
    }

    private record Next(long micros) implements Control {
    }

    private record Failure(String reason) implements Control {
    }

    private final Socket socket;
    private final Settings settings;
    private final FrameReader reader;
    private final FrameWriter writer;
    private final InterfaceRegistry registry;
    private final Map<String, InterfaceRegistry.Registered> byName = new HashMap<>();
    private final BlockingQueue<Control> control = new LinkedBlockingQueue<>();
    private final Object outputLock = new Object();
    /** In virtual time: outputs that came while an input was not acknowledged yet, reported with its acknowledgement. */
    private final List<Event> heldOutputs = new ArrayList<>();
    private boolean awaitingAck;
    private TestInterface testInterface;
    private boolean sharedClock;
    private boolean connected;
    private TronClockServer clockServer;

    private volatile AdapterContext context;
    private volatile boolean closed;
    private volatile String failure;
    private volatile boolean inTurn;
    private Thread readerThread;
    private int unacknowledged;
    private long granted;
    private TestClock.Scheduled pendingGrant;

    private TronSocketAdapter(Socket socket, Network network, Settings settings) throws IOException {
        this.socket = socket;
        this.settings = settings;
        this.reader = new FrameReader(socket, settings.frameTimeout());
        this.writer = new FrameWriter(socket);
        this.registry = new InterfaceRegistry(network);
    }

    /** Waits for an adapter to connect to {@code server}, then runs the configuration phase. */
    public static TronSocketAdapter accept(ServerSocket server, Network network, Settings settings)
            throws IOException {
        return configure(server.accept(), network, settings);
    }

    /** Connects to an adapter listening at {@code host:port} (as TRON's samples do), then configures. */
    public static TronSocketAdapter connect(String host, int port, Network network, Settings settings)
            throws IOException {
        Socket socket = new Socket();
        try {
            socket.connect(new InetSocketAddress(host, port), (int) settings.configurationTimeout().toMillis());
        } catch (IOException e) {
            socket.close();
            throw new IOException("cannot connect to the adapter at " + host + ":" + port + ": " + e.getMessage(), e);
        }
        return configure(socket, network, settings, true);
    }

    /**
     * As {@link #connect}, for an adapter that opens its port only after a while (TRON's samples in virtual time open
     * it once their threads have connected to the clock server): a refused connection is tried again every 100 ms
     * until {@code wait} has passed.
     */
    public static TronSocketAdapter connectWhenOpen(String host, int port, Network network, Settings settings,
                                                    Duration wait) throws IOException {
        long deadline = System.nanoTime() + wait.toNanos();
        while (true) {
            Socket socket = new Socket();
            try {
                socket.connect(new InetSocketAddress(host, port), (int) settings.configurationTimeout().toMillis());
            } catch (java.net.ConnectException e) {
                socket.close();
                if (System.nanoTime() - deadline >= 0) {
                    throw new IOException("cannot connect to the adapter at " + host + ":" + port + ": nothing"
                            + " listened there within " + wait.toSeconds() + " s (" + e.getMessage() + ")", e);
                }
                try {
                    Thread.sleep(100);
                } catch (InterruptedException ie) {
                    Thread.currentThread().interrupt();
                    throw new IOException("interrupted while waiting for the adapter at " + host + ":" + port, ie);
                }
                continue;
            } catch (IOException e) {
                socket.close();
                throw new IOException("cannot connect to the adapter at " + host + ":" + port + ": " + e.getMessage(),
                        e);
            }
            return configure(socket, network, settings, true);
        }
    }

    /**
     * Runs the configuration phase on a connected socket and returns the adapter for the run.
     *
     * @throws TronProtocolException when the adapter breaks the protocol, closes the connection, stays silent past
     *                               the configuration timeout, or starts after a refused registration
     */
    public static TronSocketAdapter configure(Socket socket, Network network, Settings settings)
            throws IOException {
        return configure(socket, network, settings, false);
    }

    private static TronSocketAdapter configure(Socket socket, Network network, Settings settings, boolean connected)
            throws IOException {
        Objects.requireNonNull(network, "network");
        Objects.requireNonNull(settings, "settings");
        try {
            TronSocketAdapter adapter = new TronSocketAdapter(socket, network, settings);
            adapter.connected = connected;
            adapter.configurationPhase();
            return adapter;
        } catch (IOException | RuntimeException e) {
            socket.close();
            throw e;
        }
    }

    /** The interface the adapter registered, with its time unit and timeout (null when it sent none). */
    public TestInterface testInterface() {
        return testInterface;
    }

    /** Whether the adapter asked for the shared virtual clock (DTRON's extension). */
    public boolean sharedVirtualClock() {
        return sharedClock;
    }

    /**
     * Serves the run's virtual time to the adapter's threads through {@code server} (TRON's {@code -Q PORT}): the
     * server's time becomes the run's, and the tester waits after the start, after each input and after each timed
     * wake-up until the adapter's threads are all blocked again. Call it before the run, in virtual time only.
     *
     * @throws IllegalStateException in a real-time run, or once the test has started
     */
    public void useClockServer(TronClockServer server) {
        if (!settings.virtualTime() || context != null) {
            throw new IllegalStateException(context != null ? "the test has started"
                    : "the virtual clock server needs a run in virtual time");
        }
        this.clockServer = Objects.requireNonNull(server, "server");
    }

    /** The adapter's address. */
    public String remote() {
        return socket.getInetAddress().getHostAddress() + ":" + socket.getPort();
    }

    private void configurationPhase() throws IOException {
        long deadline = System.nanoTime() + settings.configurationTimeout().toNanos();
        boolean heard = false;
        while (true) {
            reader.endFrame(); // the last command was read whole: between frames, as in the testing phase
            int command;
            try {
                command = reader.firstByte(deadline);
            } catch (EOFException e) {
                throw new TronProtocolException("the adapter closed the connection during configuration, before"
                        + " starting the test (command 64)");
            } catch (SocketTimeoutException e) {
                Duration limit = settings.configurationTimeout();
                String within = limit.toMillis() % 1000 == 0 ? limit.toSeconds() + " s" : limit.toMillis() + " ms";
                throw new TronProtocolException(!heard
                        ? "the adapter sent nothing for " + within + " during configuration; it must register"
                        + " its channels and start the test (command 64)" + silenceHint()
                        : "the adapter did not start the test (command 64) within " + within + " of configuration;"
                        + " it registered " + registry.channels().size() + " channels, then sent nothing more");
            }
            heard = true;
            switch (command) {
                case Wire.INPUT, Wire.OUTPUT -> {
                    String name = reader.string("the channel name of command " + command);
                    int known = registry.channels().size();
                    int id = registry.registerChannel(name, command == Wire.INPUT);
                    if (id > 0 && registry.channels().size() == known) {
                        LOG.debug("{} '{}' registered again: the same id {}, as TRON gives",
                                command == Wire.INPUT ? "input" : "output", name, id);
                    } else {
                        LOG.debug("register {} '{}' -> {}", command == Wire.INPUT ? "input" : "output", name, id);
                    }
                    reply(Wire.int32(id));
                }
                case Wire.INPUT_VARIABLE, Wire.OUTPUT_VARIABLE -> {
                    int channel = reader.int32("the channel id of command " + command);
                    String name = reader.string("the variable name of command " + command);
                    int result = registry.attachVariable(channel, name, command == Wire.INPUT_VARIABLE);
                    LOG.debug("attach '{}' to channel {} -> {}", name, channel, result);
                    reply(Wire.int32(result));
                }
                case Wire.TIME_UNIT -> {
                    int seconds = reader.int32("the seconds of the time unit");
                    int micros = reader.int32("the microseconds of the time unit");
                    reply(Wire.int32(registry.setTimeUnit(seconds, micros)));
                }
                case Wire.TIMEOUT -> reply(Wire.int32(registry.setTimeout(reader.int32("the timeout"))));
                case Wire.VIRTUAL_CLOCK -> {
                    sharedClock = settings.virtualTime();
                    reply(Wire.int32(sharedClock ? 0 : registry.refuseVirtualClock()));
                }
                case Wire.EXPLAIN -> reply(Wire.string(registry.explain(reader.int32("the error code to explain"))));
                case Wire.START -> {
                    String refusal = startRefusal();
                    if (refusal != null) {
                        reply(Wire.string(refusal));
                        throw new TronProtocolException("the test was not started: " + refusal);
                    }
                    // the acceptance is sent when the engine starts the run (start(AdapterContext)), so that the
                    // adapter's time 0 is the tester's, not the moment before the engine's own preparations
                    testInterface = registry.build();
                    for (InterfaceRegistry.Registered r : registry.channels()) {
                        byName.put(r.name(), r);
                    }
                    LOG.info("adapter {} configured: {}", remote(), describe());
                    reader.endFrame();
                    return;
                }
                default -> {
                    String message = "unknown command byte " + command + describeByte(command) + " during"
                            + " configuration; the commands are 1 to 6, 64 and 127";
                    registry.unknownCommand(message);
                    reply(Wire.int32(InterfaceRegistry.UNKNOWN_COMMAND));
                    throw new TronProtocolException(message);
                }
            }
        }
    }

    /** When the peer sent nothing at all: the likely reason. */
    private String silenceHint() {
        if (registry.channels().size() + registry.refusals().size() > 0) {
            return "";
        }
        return connected ? "; it sent nothing at all since the connection opened: is something else listening on"
                + " port " + socket.getPort() + "?" : "; it sent nothing at all since it connected: is the peer at "
                + remote() + " a TRON adapter?";
    }

    private static String describeByte(int b) {
        if (b >= 32 && b < 127) {
            return " (the character '" + (char) b + "': was the previous string longer than its announced length?)";
        }
        return "";
    }

    private String startRefusal() {
        List<String> refusals = registry.refusals();
        if (!refusals.isEmpty()) {
            return refusals.size() + " registration" + (refusals.size() == 1 ? " was" : "s were") + " refused: "
                    + String.join("; ", refusals);
        }
        if (registry.channels().isEmpty()) {
            return "no input or output channel was registered";
        }
        return null;
    }

    private String describe() {
        StringBuilder sb = new StringBuilder();
        for (InterfaceRegistry.Registered r : registry.channels()) {
            sb.append(r.input() ? "input " : "output ").append(r.name()).append('(');
            sb.append(String.join(", ", r.variables().stream().map(TestInterface.AttachedVariable::name).toList()));
            sb.append("), ");
        }
        sb.append("time unit ").append(testInterface.timeUnitMicros() == null ? "not set"
                : testInterface.timeUnitMicros() + " us");
        sb.append(", timeout ").append(testInterface.timeout() == null ? "not set" : testInterface.timeout());
        return sb.append(sharedClock ? ", shared virtual clock" : "").toString();
    }

    private void reply(byte[] frame) throws IOException {
        writer.write(frame);
    }

    /**
     * Refuses the adapter's start with {@code reason}, its reply to command 64, and closes the connection: for a
     * configuration the adapter completed that the tester's own settings do not go with (a timeout of the tester's
     * that makes the run, in the adapter's time unit, longer than DTRON can time; another time unit). Call it instead
     * of running the test.
     *
     * @throws IllegalStateException if the test has started
     */
    public void refuse(String reason) {
        if (context != null) {
            throw new IllegalStateException("the test has started; it cannot be refused");
        }
        try {
            reply(Wire.string(reason));
        } catch (IOException e) {
            LOG.debug("cannot refuse the start: {}", e.getMessage());
        }
        close();
    }

    @Override
    public void start(AdapterContext runContext) {
        this.context = runContext;
        try {
            reply(Wire.string(""));
        } catch (IOException e) {
            fail("cannot accept the adapter's start: " + e.getMessage());
            return;
        }
        readerThread = new Thread(this::readLoop, "tron-tester-reader");
        readerThread.setDaemon(true);
        readerThread.start();
        if (clockServer != null) {
            clockServer.attach(runContext.clock(), settings.replyTimeout(), this::fail);
            awaitQuiet();
        }
        if (sharedClock) {
            granted = runContext.clock().nowMicros();
            inTurn = true;
            awaitTurn("its first clock message after the start");
        }
    }

    @Override
    public void perform(Event input) {
        if (failure != null || closed) {
            return;
        }
        InterfaceRegistry.Registered channel = byName.get(input.channel());
        if (channel == null || !channel.input()) {
            fail("the engine applied '" + input.channel() + "', which the adapter did not register as an input");
            return;
        }
        byte[] frame = Wire.event(channel.id(), Wire.values(channel.variables(), input));
        if (sharedClock) {
            long now = context.clock().nowMicros();
            if (now > granted && !grant(now)) {
                return;
            }
            inTurn = true;
            if (send(frame, input)) {
                unacknowledged++;
                awaitTurn("an acknowledgement of input " + input + " and its next timer");
            }
        } else if (settings.virtualTime()) {
            synchronized (outputLock) {
                awaitingAck = true;
            }
            if (send(frame, input)) {
                unacknowledged++;
                if (awaitTurn("an acknowledgement of input " + input) && clockServer != null) {
                    awaitQuiet();
                }
            }
        } else {
            send(frame, input);
        }
    }

    /** With the clock server: waits until the adapter's threads are all blocked, so that time may move on. */
    private void awaitQuiet() {
        String stuck = clockServer.awaitQuiet(settings.replyTimeout());
        if (stuck != null) {
            fail(stuck);
        }
    }

    private boolean send(byte[] frame, Event input) {
        try {
            writer.write(frame);
            return true;
        } catch (IOException e) {
            fail("cannot send input " + input + " to the adapter: " + e.getMessage());
            return false;
        }
    }

    /** Grants time {@code micros} to the adapter and waits for its answer. On the engine's thread. */
    private boolean grant(long micros) {
        if (pendingGrant != null) {
            pendingGrant.cancel();
            pendingGrant = null;
        }
        inTurn = true;
        granted = micros;
        try {
            writer.write(Wire.clock(micros));
        } catch (IOException e) {
            fail("cannot send the time to the adapter: " + e.getMessage());
            return false;
        }
        return awaitTurn("its answer to the time grant t=" + micros + " us");
    }

    /**
     * Waits on the engine's thread until every input sent is acknowledged and, with the shared clock, the adapter's
     * next timer has come (then the next grant is scheduled). Returns false when the run failed meanwhile.
     */
    private boolean awaitTurn(String what) {
        boolean needNext = sharedClock;
        long deadline = System.nanoTime() + settings.replyTimeout().toNanos();
        try {
            while (unacknowledged > 0 || needNext) {
                Control c = control.poll(deadline - System.nanoTime(), TimeUnit.NANOSECONDS);
                if (c == null) {
                    int unjudged = dropHeldOutputs();
                    fail("the adapter did not send " + what + " within " + settings.replyTimeout().toMillis()
                            + " ms; in virtual time it must acknowledge every input"
                            + (sharedClock ? " and answer every time grant" : " (is it running in real time?)")
                            + (unjudged > 0 ? "; the " + unjudged + " output" + (unjudged == 1 ? "" : "s")
                            + " it sent meanwhile " + (unjudged == 1 ? "was" : "were") + " not judged" : ""));
                    return false;
                }
                if (c instanceof Failure) {
                    return false;
                }
                if (c instanceof Ack) {
                    unacknowledged -= ((Ack) c).count();
                    if (unacknowledged < 0) {
                        fail("the adapter acknowledged more events than it was sent");
                        return false;
                    }
                } else if (c instanceof Next) {
                    needNext = false;
                    if (!scheduleGrant(((Next) c).micros())) {
                        return false;
                    }
                }
            }
            return true;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            fail("interrupted while waiting for " + what);
            return false;
        } finally {
            inTurn = false;
        }
    }

    /** Forgets the outputs held for an acknowledgement that did not come; how many there were. */
    private int dropHeldOutputs() {
        synchronized (outputLock) {
            int n = heldOutputs.size();
            heldOutputs.clear();
            awaitingAck = false;
            return n;
        }
    }

    private boolean scheduleGrant(long next) {
        if (next == Wire.NO_TIMER) {
            return true;
        }
        if (next < granted) {
            fail("the adapter's next timer at " + next + " us is before the time it was already given (" + granted
                    + " us)");
            return false;
        }
        long delay = Math.max(0, next - context.clock().nowMicros());
        pendingGrant = context.clock().schedule(delay, () -> {
            pendingGrant = null;
            if (failure == null && !closed) {
                grant(next);
            }
        });
        return true;
    }

    private void readLoop() {
        try {
            while (!closed) {
                int first;
                try {
                    first = reader.firstInt();
                } catch (EOFException e) {
                    fail("the adapter closed the connection");
                    return;
                }
                if (!readFrame(first)) {
                    return;
                }
                reader.endFrame();
            }
        } catch (IOException e) {
            if (!closed) {
                fail(e instanceof TronProtocolException ? "protocol error: " + e.getMessage()
                        : "the connection to the adapter failed: " + e.getMessage());
            }
        }
    }

    /** Reads the rest of a frame that began with {@code first}; returns false when the run failed. */
    private boolean readFrame(int first) throws IOException {
        if ((first & Wire.ACK_BIT) != 0) {
            int count = first & ~Wire.ACK_BIT;
            if (count == 0 || count > MAX_ACK_COUNT) {
                // no acknowledgement counts that many events: a negative number where a channel id belongs
                fail(String.format("protocol error: the adapter sent an event on channel id %d (0x%08x): channel ids"
                        + " are positive (%s)", first, first, registry.registeredList()));
                return false;
            }
            if (!settings.virtualTime()) {
                fail(String.format("protocol error: the adapter sent an acknowledgement (0x%08x) in a real-time run;"
                        + " acknowledgements are for virtual time (is the adapter set to virtual time?)", first));
                return false;
            }
            synchronized (outputLock) {
                for (Event held : heldOutputs) {
                    LOG.debug("output {} (before the acknowledgement)", held);
                    context.report(held);
                }
                heldOutputs.clear();
                awaitingAck = false;
            }
            control.add(new Ack(count));
            return true;
        }
        if (first == Wire.CLOCK_CHANNEL && sharedClock) {
            int n = reader.uint16("the length of a clock message");
            if (n != 2) {
                fail("protocol error: a clock message from the adapter has " + n + " values instead of 2");
                return false;
            }
            long micros = Wire.clockMicros(reader.int32("a clock message's high word"),
                    reader.int32("a clock message's low word"));
            control.add(new Next(micros));
            return true;
        }
        InterfaceRegistry.Registered channel = registry.channel(first).orElse(null);
        if (channel == null) {
            fail("protocol error: the adapter sent an event on channel id " + first + ", which was never registered ("
                    + registry.registeredList() + ")");
            return false;
        }
        if (channel.input()) {
            fail("protocol error: the adapter sent an event on channel id " + first + " ('" + channel.name()
                    + "'), which is an input; the adapter sends only outputs");
            return false;
        }
        List<TestInterface.AttachedVariable> vars = channel.variables();
        int n = reader.uint16("the number of values of an event on '" + channel.name() + "'");
        if (n != vars.size()) {
            fail("protocol error: the adapter sent an event on '" + channel.name() + "' (id " + first + ") with " + n
                    + " values; it carries " + vars.size() + " " + vars.stream()
                    .map(TestInterface.AttachedVariable::name).toList());
            return false;
        }
        Map<String, Integer> values = new LinkedHashMap<>();
        for (int i = 0; i < n; i++) {
            values.put(vars.get(i).name(), reader.int32("value " + (i + 1) + " of " + n + " of an event on '"
                    + channel.name() + "'"));
        }
        Event event = new Event(channel.name(), values);
        if (sharedClock && !inTurn) {
            fail("protocol error: the adapter sent output " + event + " outside its turn; with the shared virtual"
                    + " clock, outputs are sent only in answer to a time grant or an input");
            return false;
        }
        if (settings.virtualTime()) {
            // taken (reported, or held for an input's acknowledgement) before it is acknowledged: the adapter's
            // thread goes on, and may let virtual time move, only once the tester has it
            synchronized (outputLock) {
                if (awaitingAck && !sharedClock) {
                    heldOutputs.add(event);
                } else {
                    LOG.debug("output {}", event);
                    context.report(event);
                }
            }
            writer.write(Wire.ack(1));
        } else {
            // an output happened when its first byte came, not when its last did
            long late = (System.nanoTime() - reader.frameStartNanos()) / 1000;
            long at = Math.max(0, context.clock().nowMicros() - late);
            LOG.debug("output {} at {} us", event, at);
            context.report(event, at);
        }
        return true;
    }

    /**
     * Before the engine declares a missed deadline: an adapter in the middle of a frame is waited for until the frame
     * is complete (its output then counts from its first byte) or its frame timeout passes (then the run is
     * INCONCLUSIVE: the frame was truncated).
     */
    @Override
    public Optional<String> unreachable() {
        long deadline = reader.frameStartNanos() + reader.frameTimeout().toNanos() + 200_000_000L;
        while (reader.inFrame() && failure == null && !closed && System.nanoTime() - deadline < 0) {
            try {
                Thread.sleep(1);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                break;
            }
        }
        String why = failure;
        if (why != null) {
            return Optional.of(why);
        }
        if (reader.inFrame()) {
            return Optional.of("a frame from the adapter began "
                    + (System.nanoTime() - reader.frameStartNanos()) / 1_000_000 + " ms ago and is not complete");
        }
        return Optional.empty();
    }

    private void fail(String reason) {
        synchronized (this) {
            if (failure != null || closed) {
                return;
            }
            failure = reason;
        }
        LOG.debug("run fails: {}", reason);
        control.add(new Failure(reason));
        AdapterContext c = context;
        if (c != null) {
            c.inconclusive(reason);
        }
        closeSocket();
    }

    @Override
    public void stop() {
        close();
    }

    /** Ends the connection. */
    @Override
    public void close() {
        closed = true;
        closeSocket();
        Thread t = readerThread;
        if (t != null && t != Thread.currentThread()) {
            try {
                t.join(1000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
    }

    private void closeSocket() {
        try {
            socket.close();
        } catch (IOException e) {
            LOG.debug("closing the socket: {}", e.getMessage());
        }
    }
}
