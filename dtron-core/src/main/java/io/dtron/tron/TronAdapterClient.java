package io.dtron.tron;

import io.dtron.tron.internal.FrameReader;
import io.dtron.tron.internal.FrameWriter;
import io.dtron.tron.internal.Wire;
import java.io.Closeable;
import java.io.EOFException;
import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.time.Duration;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;
import java.util.PriorityQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The system under test's side of TRON's socket-adapter protocol, shaped like TRON's Java API: a reporter that
 * registers input and output channels with their variables, sets the time unit and the timeout, starts the test
 * and reports outputs; and an {@link InputHandler} whose {@code perform} applies the inputs the tester sends. It
 * talks to Uppaal TRON or to DTRON in TRON's place ({@link TronSocketAdapter}).
 *
 * <p>Configuration is synchronous: each call sends a command and waits for the tester's reply; a refusal (a
 * negative error code) is asked to be explained (command 127) and thrown as a {@link TronProtocolException}. After
 * {@link #start}, a reader thread receives inputs and, in virtual time, acknowledgements; writes are serialised.
 *
 * <p>Time modes ({@link TimeMode}):
 * <ul>
 *   <li>{@code REAL_TIME}: inputs and timers ({@link #schedule}) run on one thread of this client, one at a time,
 *       on the wall clock; outputs may be reported from any thread.</li>
 *   <li>{@code VIRTUAL_ACKS}: TRON's virtual-time acknowledgements: each input is acknowledged once its handler has
 *       returned, so outputs reported by the handler are seen at the input's instant; timers run on the wall
 *       clock, and what they report is seen at whatever virtual time the tester has then.</li>
 *   <li>{@code SHARED_VIRTUAL_CLOCK}: DTRON's extension (command 200): timers run on the tester's virtual clock.
 *       The client runs every callback (inputs and timers) on its reader thread when the tester grants the time,
 *       and tells the tester its next timer after each turn. Outputs and timers may only be reported and scheduled
 *       from callbacks (or before {@link #start}). Works with DTRON only: TRON refuses command 200.</li>
 * </ul>
 */
public final class TronAdapterClient implements Closeable {
    private static final Logger LOG = LoggerFactory.getLogger(TronAdapterClient.class);
    private static final Duration FRAME_TIMEOUT = Duration.ofSeconds(5);
    private static final Duration REPLY_TIMEOUT = Duration.ofSeconds(30);

    /** How the client keeps time with the tester. */
    public enum TimeMode {
        /** The wall clock, no acknowledgements. */
        REAL_TIME,
        /** TRON's virtual time: every event is acknowledged; timers on the wall clock. */
        VIRTUAL_ACKS,
        /** DTRON's shared virtual clock: acknowledgements, and timers on the tester's virtual clock. */
        SHARED_VIRTUAL_CLOCK
    }

    /** Applies the inputs the tester sends (TRON's {@code Adapter.perform}). */
    @FunctionalInterface
    public interface InputHandler {
        /** Applies input {@code channel} (the id from {@link #registerInput}) with its variables' values. */
        void perform(int channel, int[] values);
    }

    /** A timer set with {@link #schedule}. */
    public interface Scheduled {
        /** Prevents the timer from running if it has not run yet. */
        void cancel();
    }

    private record Channel(String name, boolean input, AtomicInteger variables) {
    }

    private static final class Timer implements Comparable<Timer>, Scheduled {
        final long due;
        final long seq;
        final Runnable task;
        volatile boolean cancelled;

        Timer(long due, long seq, Runnable task) {
            this.due = due;
            this.seq = seq;
            this.task = task;
        }

        @Override
        public int compareTo(Timer o) {
            return due != o.due ? Long.compare(due, o.due) : Long.compare(seq, o.seq);
        }

        @Override
        public void cancel() {
            cancelled = true;
        }
    }

    private final Socket socket;
    private final TimeMode mode;
    private final FrameReader reader;
    private final FrameWriter writer;
    private final Map<Integer, Channel> channels = new LinkedHashMap<>();
    private final CountDownLatch ended = new CountDownLatch(1);
    private final AtomicInteger acknowledged = new AtomicInteger();
    private final PriorityQueue<Timer> timers = new PriorityQueue<>();
    private ScheduledExecutorService executor;
    private InputHandler handler;
    private Thread readerThread;
    private volatile boolean started;
    private volatile boolean closed;
    private volatile String failure;
    private volatile long startNanos;
    private long virtualNow;
    private long timerSeq;

    private TronAdapterClient(Socket socket, TimeMode mode) throws IOException {
        this.socket = socket;
        this.mode = Objects.requireNonNull(mode, "mode");
        this.reader = new FrameReader(socket, FRAME_TIMEOUT);
        this.writer = new FrameWriter(socket);
    }

    /** Connects to a tester listening at {@code host:port}. */
    public static TronAdapterClient connect(String host, int port, TimeMode mode) throws IOException {
        Socket socket = new Socket();
        try {
            socket.connect(new InetSocketAddress(host, port), (int) REPLY_TIMEOUT.toMillis());
            return new TronAdapterClient(socket, mode);
        } catch (IOException e) {
            socket.close();
            throw new IOException("cannot connect to the tester at " + host + ":" + port + ": " + e.getMessage(), e);
        }
    }

    /** Waits for the tester to connect to {@code server} (as TRON's sample adapters do). */
    public static TronAdapterClient accept(ServerSocket server, TimeMode mode) throws IOException {
        return over(server.accept(), mode);
    }

    /** A client on a connected socket. */
    public static TronAdapterClient over(Socket socket, TimeMode mode) throws IOException {
        return new TronAdapterClient(socket, mode);
    }

    /** Registers an input channel and returns its id. */
    public int registerInput(String name) throws IOException {
        return registerChannel(Wire.INPUT, name);
    }

    /** Registers an output channel and returns its id. */
    public int registerOutput(String name) throws IOException {
        return registerChannel(Wire.OUTPUT, name);
    }

    private synchronized int registerChannel(int command, String name) throws IOException {
        requireConfiguring();
        String kind = command == Wire.INPUT ? "input" : "output";
        int id = request(Wire.command(command, name), kind + " '" + name + "'");
        if (channels.containsKey(id)) {
            throw new TronProtocolException("the tester gave " + kind + " '" + name + "' the id " + id + ", which it"
                    + " already gave '" + channels.get(id).name() + "'");
        }
        channels.put(id, new Channel(name, command == Wire.INPUT, new AtomicInteger()));
        return id;
    }

    /** Attaches a global variable of the model to an input; its value travels with the input's events. */
    public void addInputVariable(int channel, String variable) throws IOException {
        attach(Wire.INPUT_VARIABLE, channel, variable);
    }

    /** Attaches a global variable of the model to an output. */
    public void addOutputVariable(int channel, String variable) throws IOException {
        attach(Wire.OUTPUT_VARIABLE, channel, variable);
    }

    private synchronized void attach(int command, int channel, String variable) throws IOException {
        requireConfiguring();
        request(Wire.command(command, channel, variable), "variable '" + variable + "' of channel id " + channel);
        Channel c = channels.get(channel);
        if (c != null) {
            c.variables().incrementAndGet();
        }
    }

    /** Sets the model time unit in microseconds. */
    public synchronized void setTimeUnit(long micros) throws IOException {
        requireConfiguring();
        if (micros <= 0) {
            throw new IllegalArgumentException("the time unit must be a positive number of microseconds");
        }
        request(Wire.command(Wire.TIME_UNIT, (int) (micros / 1_000_000), (int) (micros % 1_000_000)),
                "time unit " + micros + " us");
    }

    /** Sets the test's timeout in model time units. */
    public synchronized void setTimeout(int units) throws IOException {
        requireConfiguring();
        request(Wire.command(Wire.TIMEOUT, units), "timeout " + units);
    }

    /** The tester's explanation of an error code (command 127); during configuration only. */
    public synchronized String explain(int code) throws IOException {
        requireConfiguring();
        writer.write(Wire.command(Wire.EXPLAIN, code));
        return reader.stringReply(deadline(), "the explanation of error " + code);
    }

    /**
     * Starts the test: from now on the tester sends inputs to {@code inputs}.
     *
     * @throws TronProtocolException when the tester refuses to start, with its reason
     */
    public synchronized void start(InputHandler inputs) throws IOException {
        requireConfiguring();
        this.handler = Objects.requireNonNull(inputs, "inputs");
        if (mode == TimeMode.SHARED_VIRTUAL_CLOCK) {
            request(Wire.command(Wire.VIRTUAL_CLOCK), "the shared virtual clock");
        }
        writer.write(new byte[] {(byte) Wire.START});
        String refusal = reader.stringReply(deadline(), "the answer to start");
        if (!refusal.isEmpty()) {
            close();
            throw new TronProtocolException("the tester refused to start: " + refusal);
        }
        started = true;
        startNanos = System.nanoTime();
        if (mode == TimeMode.SHARED_VIRTUAL_CLOCK) {
            writer.write(Wire.clock(nextTimer()));
        } else {
            executor = Executors.newSingleThreadScheduledExecutor(r -> {
                Thread t = new Thread(r, "tron-adapter");
                t.setDaemon(true);
                return t;
            });
        }
        readerThread = new Thread(this::readLoop, "tron-adapter-reader");
        readerThread.setDaemon(true);
        readerThread.start();
    }

    private int request(byte[] frame, String what) throws IOException {
        writer.write(frame);
        int answer = reader.int32Reply(deadline(), "the answer about " + what);
        if (answer < 0) {
            String explanation;
            try {
                explanation = explain(answer);
            } catch (IOException e) {
                explanation = "(no explanation: " + e.getMessage() + ")";
            }
            throw new TronProtocolException("the tester refused " + what + " (error " + answer + "): " + explanation,
                    answer);
        }
        return answer;
    }

    private long deadline() {
        return System.nanoTime() + REPLY_TIMEOUT.toNanos();
    }

    private void requireConfiguring() {
        if (started) {
            throw new IllegalStateException("the test has started; configure before start()");
        }
    }

    /**
     * Reports an output with its variables' values, in the order they were attached. Returns false when the
     * connection is gone (the test has ended), true when sent.
     *
     * @throws IllegalArgumentException when {@code channel} is not a registered output or the number of values is
     *                                  wrong
     * @throws IllegalStateException    with the shared virtual clock, when called outside a callback
     */
    public boolean reportOutput(int channel, int... values) {
        Channel c = channels.get(channel);
        if (c == null || c.input()) {
            throw new IllegalArgumentException("channel id " + channel + " is not a registered output");
        }
        if (values.length != c.variables().get()) {
            throw new IllegalArgumentException("output '" + c.name() + "' carries " + c.variables().get()
                    + " values, not " + values.length);
        }
        if (!started) {
            throw new IllegalStateException("report outputs after start()");
        }
        requireCallbackThread("report outputs");
        try {
            writer.write(Wire.event(channel, values));
            return true;
        } catch (IOException e) {
            LOG.debug("output '{}' not sent, the connection is gone (the test has ended): {}", c.name(),
                    e.getMessage());
            close();
            return false;
        }
    }

    /** Microseconds since the start of the test: the wall clock, or the shared virtual clock. */
    public long nowMicros() {
        if (mode == TimeMode.SHARED_VIRTUAL_CLOCK) {
            synchronized (timers) {
                return virtualNow;
            }
        }
        return started ? (System.nanoTime() - startNanos) / 1000 : 0;
    }

    /**
     * Runs {@code task} {@code delayMicros} from now, on the client's callback thread (never at the same time as an
     * input or another timer).
     */
    public Scheduled schedule(long delayMicros, Runnable task) {
        Objects.requireNonNull(task, "task");
        if (mode == TimeMode.SHARED_VIRTUAL_CLOCK) {
            requireCallbackThread("schedule timers");
            synchronized (timers) {
                Timer t = new Timer(virtualNow + Math.max(0, delayMicros), timerSeq++, task);
                timers.add(t);
                return t;
            }
        }
        if (executor == null) {
            throw new IllegalStateException("schedule timers after start()");
        }
        ScheduledFuture<?> f = executor.schedule(() -> runCallback(task), Math.max(0, delayMicros),
                TimeUnit.MICROSECONDS);
        return () -> f.cancel(false);
    }

    private void requireCallbackThread(String what) {
        if (mode == TimeMode.SHARED_VIRTUAL_CLOCK && started && Thread.currentThread() != readerThread) {
            throw new IllegalStateException("with the shared virtual clock, " + what + " only from the client's"
                    + " callbacks (inputs and timers)");
        }
    }

    /**
     * Waits until the test ends: the tester closes the connection (its normal end of a test, whatever the verdict),
     * the connection is lost, or the client meets a protocol error ({@link #failure()}). True if it has ended.
     */
    public boolean awaitEnd(Duration timeout) throws InterruptedException {
        return ended.await(timeout.toMillis(), TimeUnit.MILLISECONDS);
    }

    /** The protocol error that ended the test on this side, if any (not the tester's normal end of the test). */
    public Optional<String> failure() {
        return Optional.ofNullable(failure);
    }

    /** How many of this client's outputs the tester has acknowledged (virtual time). */
    public int outputsAcknowledged() {
        return acknowledged.get();
    }

    private void readLoop() {
        try {
            while (!closed) {
                int first;
                try {
                    first = reader.firstInt();
                } catch (EOFException e) {
                    LOG.debug("the tester closed the connection");
                    return;
                }
                if (!readFrame(first)) {
                    return;
                }
            }
        } catch (TronProtocolException e) {
            if (!closed) {
                fail("protocol error: " + e.getMessage());
            }
        } catch (IOException e) {
            LOG.debug("the connection to the tester ended: {}", e.getMessage());
        } finally {
            close();
        }
    }

    private boolean readFrame(int first) throws IOException {
        if ((first & Wire.ACK_BIT) != 0) {
            if (mode == TimeMode.REAL_TIME) {
                fail("protocol error: the tester sent an acknowledgement in a real-time test");
                return false;
            }
            acknowledged.addAndGet(first & ~Wire.ACK_BIT);
            return true;
        }
        if (first == Wire.CLOCK_CHANNEL && mode == TimeMode.SHARED_VIRTUAL_CLOCK) {
            int n = reader.uint16("the length of a clock message");
            if (n != 2) {
                fail("protocol error: a clock message from the tester has " + n + " values instead of 2");
                return false;
            }
            long micros = Wire.clockMicros(reader.int32("a clock message's high word"),
                    reader.int32("a clock message's low word"));
            return granted(micros);
        }
        Channel c = channels.get(first);
        if (c == null || !c.input()) {
            fail("protocol error: the tester sent an event on channel id " + first + ", which is not a registered"
                    + " input");
            return false;
        }
        int n = reader.uint16("the number of values of input '" + c.name() + "'");
        if (n != c.variables().get()) {
            fail("protocol error: the tester sent input '" + c.name() + "' with " + n + " values instead of "
                    + c.variables().get());
            return false;
        }
        int[] values = new int[n];
        for (int i = 0; i < n; i++) {
            values[i] = reader.int32("value " + (i + 1) + " of input '" + c.name() + "'");
        }
        return input(first, values);
    }

    private boolean input(int channel, int[] values) throws IOException {
        switch (mode) {
            case REAL_TIME -> executor.execute(() -> runCallback(() -> handler.perform(channel, values)));
            case VIRTUAL_ACKS -> {
                Future<?> done = executor.submit(() -> runCallback(() -> handler.perform(channel, values)));
                try {
                    done.get();
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    return false;
                } catch (ExecutionException e) {
                    fail("the input handler failed: " + e.getCause());
                    return false;
                }
                writer.write(Wire.ack(1));
            }
            default -> {
                runCallback(() -> handler.perform(channel, values));
                writer.write(Wire.ack(1));
                writer.write(Wire.clock(nextTimer()));
            }
        }
        return !closed;
    }

    /** The shared clock reached {@code micros}: runs the timers due, then tells the next one. */
    private boolean granted(long micros) throws IOException {
        synchronized (timers) {
            if (micros < virtualNow) {
                fail("protocol error: the tester granted t=" + micros + " us, before the current t=" + virtualNow);
                return false;
            }
        }
        while (true) {
            Timer due;
            synchronized (timers) {
                due = timers.peek();
                if (due == null || due.due > micros) {
                    virtualNow = micros;
                    break;
                }
                timers.poll();
                virtualNow = Math.max(virtualNow, due.due);
            }
            if (!due.cancelled) {
                runCallback(due.task);
            }
        }
        writer.write(Wire.clock(nextTimer()));
        return !closed;
    }

    private long nextTimer() {
        synchronized (timers) {
            while (!timers.isEmpty() && timers.peek().cancelled) {
                timers.poll();
            }
            return timers.isEmpty() ? Wire.NO_TIMER : timers.peek().due;
        }
    }

    private void runCallback(Runnable task) {
        if (closed) {
            return;
        }
        try {
            task.run();
        } catch (RuntimeException e) {
            LOG.error("an adapter callback failed", e);
        }
    }

    private void fail(String reason) {
        synchronized (this) {
            if (failure != null) {
                return;
            }
            failure = reason;
        }
        LOG.warn("{}", reason);
        close();
    }

    /** Closes the connection; the tester sees the adapter leave. */
    @Override
    public void close() {
        closed = true;
        try {
            socket.close();
        } catch (IOException e) {
            LOG.debug("closing the socket: {}", e.getMessage());
        }
        if (executor != null) {
            executor.shutdownNow();
        }
        ended.countDown();
    }
}
