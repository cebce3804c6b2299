package io.dtron.tron;

import io.dtron.engine.TestClock;
import io.dtron.tron.internal.ClockProtocol;
import java.io.Closeable;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.EOFException;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.net.SocketException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.Consumer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * TRON's virtual clock server ({@code tron -Q PORT}, {@code dtron tron -Q PORT}): the threads of an adapter written
 * against TRON's Java API ({@code VirtualThread}s) connect to it, one connection each, and take their time, their
 * mutexes, their condition waits and their timed waits from it, so that a TRON sample runs unchanged in virtual time.
 *
 * <p>Virtual time is the run's virtual clock: it stands still while any active thread of the adapter can run, and
 * while the tester is busy; when every active thread is blocked (on a mutex, a wait or a timed wait), the tester's
 * clock jumps to its own next step or to the earliest timed wait, whichever comes first, and that waiter is woken.
 * The tester's side ({@link TronSocketAdapter#useClockServer}) waits after the start, after each input and after each
 * wake-up until the adapter's threads are all blocked again, so no adapter thread still runs when time jumps. Before
 * the run starts, time is 0 and timed waits wait for the run.
 *
 * <p>A malformed command is logged and counted and ends that thread's connection; the server and the other threads go
 * on. The server listens on the address it is given (loopback unless the user says otherwise).
 */
public final class TronClockServer implements Closeable {
    private static final Logger LOG = LoggerFactory.getLogger(TronClockServer.class);

    private final ServerSocket server;
    private final Object lock = new Object();
    private final Map<Integer, Client> clients = new LinkedHashMap<>();
    private final Map<Integer, Mutex> mutexes = new HashMap<>();
    private final Map<Integer, List<Client>> conditions = new HashMap<>();
    private final List<Client> waitingForRun = new ArrayList<>();
    private final AtomicInteger rejected = new AtomicInteger();
    private final Thread acceptor;
    private int nextClient = 1;
    private int nextMutex = 1;
    private int nextCondition = 1;
    private int everConnected;
    private TestClock clock;
    private Duration quietTimeout = Duration.ofSeconds(10);
    private Consumer<String> onFailure = reason -> { };
    private volatile boolean closed;

    private enum State { RUNNING, LOCKING, WAITING }

    /** One connected virtual thread, as the server sees it. */
    private static final class Client {
        final int id;
        final String name;
        final Socket socket;
        boolean active = true;
        State state = State.RUNNING;
        /** The reply to send once the thread may go on, or null while it is blocked. */
        Integer reply;
        /** In a wait: its condition and mutex, the code to reply once the mutex is held again, its deadline. */
        int condition;
        int mutex;
        int wakeCode;
        long deadline = -1;
        TestClock.Scheduled timer;

        Client(int id, String name, Socket socket) {
            this.id = id;
            this.name = name;
            this.socket = socket;
        }

        @Override
        public String toString() {
            return "'" + name + "'";
        }
    }

    private static final class Mutex {
        Client owner;
        final ArrayDeque<Client> queue = new ArrayDeque<>();
    }

    private TronClockServer(ServerSocket server) {
        this.server = server;
        this.acceptor = new Thread(this::acceptLoop, "tron-clock-acceptor");
        acceptor.setDaemon(true);
    }

    /**
     * Opens the server on {@code address:port} (port 0: any free port) and starts accepting threads.
     *
     * @throws IOException when the port cannot be bound
     */
    public static TronClockServer open(InetAddress address, int port) throws IOException {
        ServerSocket socket = new ServerSocket(port, 50, address);
        TronClockServer server = new TronClockServer(socket);
        server.acceptor.start();
        LOG.debug("virtual clock server on {}:{}", address.getHostAddress(), socket.getLocalPort());
        return server;
    }

    /** The port it listens on. */
    public int port() {
        return server.getLocalPort();
    }

    /** The address it listens on. */
    public String address() {
        return server.getInetAddress().getHostAddress() + ":" + server.getLocalPort();
    }

    /** How many threads have connected so far, including those that have ended. */
    public int threadsConnected() {
        synchronized (lock) {
            return everConnected;
        }
    }

    /** How many malformed commands were rejected (each ended its thread's connection). */
    public int rejected() {
        return rejected.get();
    }

    /**
     * Takes the run's clock: from now on time is its time, and timed waits are its timers, which run on the tester's
     * thread; {@code onFailure} is told when the adapter's threads do not all block within {@code quietTimeout} after
     * a wake-up.
     */
    void attach(TestClock runClock, Duration quietTimeout, Consumer<String> onFailure) {
        synchronized (lock) {
            this.clock = runClock;
            this.quietTimeout = quietTimeout;
            this.onFailure = onFailure;
            for (Client c : waitingForRun) {
                scheduleTimeout(c);
            }
            waitingForRun.clear();
        }
    }

    /**
     * Waits until no active thread of the adapter can run (each is blocked on a mutex, a wait or a timed wait, or has
     * deactivated itself); returns null then, or after {@code timeout} the threads still running.
     */
    String awaitQuiet(Duration timeout) {
        long deadline = System.nanoTime() + timeout.toNanos();
        synchronized (lock) {
            while (true) {
                List<Client> running = running();
                if (running.isEmpty() || closed) {
                    return null;
                }
                long left = deadline - System.nanoTime();
                if (left <= 0) {
                    return "the adapter's virtual threads did not all block within " + timeout.toMillis()
                            + " ms (still running: " + running.stream().map(Client::toString).toList() + ")";
                }
                try {
                    lock.wait(Math.max(1, left / 1_000_000));
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    return "interrupted while waiting for the adapter's virtual threads to block";
                }
            }
        }
    }

    private List<Client> running() {
        List<Client> running = new ArrayList<>();
        for (Client c : clients.values()) {
            if (c.active && c.state == State.RUNNING) {
                running.add(c);
            }
        }
        return running;
    }

    private void acceptLoop() {
        while (!closed) {
            Socket socket;
            try {
                socket = server.accept();
            } catch (IOException e) {
                if (!closed) {
                    LOG.warn("the virtual clock server stopped accepting: {}", e.getMessage());
                }
                return;
            }
            Thread t = new Thread(() -> serve(socket), "tron-clock-client");
            t.setDaemon(true);
            t.start();
        }
    }

    private void serve(Socket socket) {
        Client client = null;
        try (socket) {
            socket.setTcpNoDelay(true);
            DataInputStream in = new DataInputStream(socket.getInputStream());
            DataOutputStream out = new DataOutputStream(socket.getOutputStream());
            socket.setSoTimeout(5000);
            int length = in.readUnsignedByte();
            byte[] name = new byte[length];
            in.readFully(name);
            socket.setSoTimeout(0);
            synchronized (lock) {
                client = new Client(nextClient++, new String(name, StandardCharsets.UTF_8), socket);
                clients.put(client.id, client);
                everConnected++;
                lock.notifyAll();
            }
            LOG.debug("virtual thread {} connected from {}", client, socket.getRemoteSocketAddress());
            while (!closed) {
                int command;
                try {
                    command = in.readUnsignedByte();
                } catch (EOFException e) {
                    LOG.debug("virtual thread {} closed its connection", client);
                    return;
                }
                if (command == ClockProtocol.QUIT) {
                    LOG.debug("virtual thread {} quit", client);
                    return;
                }
                LOG.trace("{} command {} at {} us", client, command, now());
                int[] reply;
                try {
                    reply = execute(client, command, in);
                } catch (ClockProtocol.Malformed e) {
                    // counted before the connection closes, so that the thread sees the count when it sees the end
                    rejected.incrementAndGet();
                    LOG.warn("virtual clock: rejected a command of thread {}: {}; its connection is closed", client,
                            e.getMessage());
                    return;
                }
                if (reply != null) {
                    for (int value : reply) {
                        out.writeInt(value);
                    }
                    out.flush();
                }
            }
        } catch (SocketException | EOFException e) {
            if (!closed) {
                LOG.debug("virtual thread {}: {}", client, e.getMessage());
            }
        } catch (IOException e) {
            if (!closed) {
                LOG.warn("virtual thread {}: {}", client, e.getMessage());
            }
        } finally {
            if (client != null) {
                remove(client);
            }
        }
    }

    /** Runs one command; returns the reply's int32 values, or null for none. Blocks while the command blocks. */
    private int[] execute(Client c, int command, DataInputStream in) throws IOException {
        switch (command) {
            case ClockProtocol.DEACTIVATE, ClockProtocol.ACTIVATE -> {
                synchronized (lock) {
                    c.active = command == ClockProtocol.ACTIVATE;
                    lock.notifyAll();
                }
                return new int[] {ClockProtocol.OK};
            }
            case ClockProtocol.MUTEX_INIT -> {
                synchronized (lock) {
                    int id = nextMutex++;
                    mutexes.put(id, new Mutex());
                    return new int[] {id};
                }
            }
            case ClockProtocol.MUTEX_DESTROY -> {
                int id = in.readInt();
                synchronized (lock) {
                    Mutex m = mutexes.get(id);
                    if (m != null && m.owner == null && m.queue.isEmpty()) {
                        mutexes.remove(id);
                    }
                }
                return null;
            }
            case ClockProtocol.MUTEX_LOCK -> {
                int id = in.readInt();
                synchronized (lock) {
                    lock(c, mutex(id), ClockProtocol.OK);
                }
                return new int[] {awaitReply(c)};
            }
            case ClockProtocol.MUTEX_UNLOCK -> {
                int id = in.readInt();
                synchronized (lock) {
                    Mutex m = mutex(id);
                    if (m.owner != c) {
                        return new int[] {ClockProtocol.ERROR};
                    }
                    unlock(m);
                }
                return new int[] {ClockProtocol.OK};
            }
            case ClockProtocol.CONDITION_INIT -> {
                synchronized (lock) {
                    int id = nextCondition++;
                    conditions.put(id, new ArrayList<>());
                    return new int[] {id};
                }
            }
            case ClockProtocol.CONDITION_DESTROY -> {
                int id = in.readInt();
                synchronized (lock) {
                    List<Client> waiters = conditions.get(id);
                    if (waiters != null && waiters.isEmpty()) {
                        conditions.remove(id);
                    }
                }
                return null;
            }
            case ClockProtocol.WAIT -> {
                int condition = in.readInt();
                int mutex = in.readInt();
                synchronized (lock) {
                    if (!startWait(c, condition, mutex, -1)) {
                        return new int[] {ClockProtocol.ERROR};
                    }
                }
                return new int[] {awaitReply(c)};
            }
            case ClockProtocol.TIMED_WAIT, ClockProtocol.DELAY -> {
                int condition = in.readInt();
                int mutex = in.readInt();
                long seconds = in.readInt();
                long micros = in.readInt();
                long time = seconds * 1_000_000 + micros;
                synchronized (lock) {
                    long deadline = command == ClockProtocol.DELAY ? now() + Math.max(0, time) : time;
                    if (!startWait(c, condition, mutex, Math.max(0, deadline))) {
                        return new int[] {ClockProtocol.ERROR};
                    }
                }
                return new int[] {awaitReply(c)};
            }
            case ClockProtocol.SIGNAL, ClockProtocol.BROADCAST -> {
                int condition = in.readInt();
                synchronized (lock) {
                    List<Client> waiters = condition(condition);
                    int n = command == ClockProtocol.SIGNAL ? Math.min(1, waiters.size()) : waiters.size();
                    for (Client w : new ArrayList<>(waiters.subList(0, n))) {
                        wake(w, ClockProtocol.OK);
                    }
                }
                return command == ClockProtocol.SIGNAL ? new int[] {ClockProtocol.OK} : null;
            }
            case ClockProtocol.GET_TIME -> {
                long now;
                synchronized (lock) {
                    now = now();
                }
                return new int[] {(int) (now / 1_000_000), (int) (now % 1_000_000)};
            }
            default -> throw new ClockProtocol.Malformed("unknown command byte " + command
                    + "; the commands are 1 to 14 and 127");
        }
    }

    private Mutex mutex(int id) throws ClockProtocol.Malformed {
        Mutex m = mutexes.get(id);
        if (m == null) {
            throw new ClockProtocol.Malformed("no mutex has id " + id);
        }
        return m;
    }

    private List<Client> condition(int id) throws ClockProtocol.Malformed {
        List<Client> waiters = conditions.get(id);
        if (waiters == null) {
            throw new ClockProtocol.Malformed("no condition has id " + id);
        }
        return waiters;
    }

    private long now() {
        return clock == null ? 0 : clock.nowMicros();
    }

    /** Under the lock: {@code c} takes {@code m}, or queues for it; replies {@code code} once it holds it. */
    private void lock(Client c, Mutex m, int code) {
        if (m.owner == null) {
            m.owner = c;
            release(c, code);
        } else {
            c.state = State.LOCKING;
            c.wakeCode = code;
            m.queue.add(c);
            lock.notifyAll();
        }
    }

    private void unlock(Mutex m) {
        Client next = m.queue.poll();
        m.owner = next;
        if (next != null) {
            release(next, next.wakeCode);
        }
    }

    /** Under the lock: {@code c} may go on, with {@code code} as its reply. */
    private void release(Client c, int code) {
        c.state = State.RUNNING;
        c.reply = code;
        lock.notifyAll();
    }

    private boolean startWait(Client c, int condition, int mutex, long deadline) throws ClockProtocol.Malformed {
        List<Client> waiters = condition(condition);
        Mutex m = mutex(mutex);
        if (m.owner != c) {
            return false;
        }
        unlock(m);
        c.state = State.WAITING;
        c.condition = condition;
        c.mutex = mutex;
        c.deadline = deadline;
        waiters.add(c);
        if (deadline >= 0) {
            if (clock == null) {
                waitingForRun.add(c);
            } else {
                scheduleTimeout(c);
            }
        }
        lock.notifyAll();
        return true;
    }

    /** Under the lock: a timer on the run's clock that wakes {@code c} at its deadline, timed out. */
    private void scheduleTimeout(Client c) {
        long deadline = c.deadline;
        LOG.trace("{} waits until {} us (now {} us)", c, deadline, clock.nowMicros());
        c.timer = clock.schedule(Math.max(0, deadline - clock.nowMicros()), () -> timedOut(c, deadline));
    }

    /** On the tester's thread, at {@code deadline}: wakes {@code c} if it still waits, then waits for quiet. */
    private void timedOut(Client c, long deadline) {
        synchronized (lock) {
            if (c.state != State.WAITING || c.deadline != deadline || !clients.containsKey(c.id)) {
                return;
            }
            wake(c, ClockProtocol.TIMED_OUT);
        }
        LOG.trace("{} timed out at {} us", c, deadline);
        String stuck = awaitQuiet(quietTimeout);
        if (stuck != null) {
            onFailure.accept(stuck);
        }
    }

    /** Under the lock: ends {@code c}'s wait with {@code code}, once it holds its mutex again. */
    private void wake(Client c, int code) {
        List<Client> waiters = conditions.get(c.condition);
        if (waiters != null) {
            waiters.remove(c);
        }
        if (c.timer != null) {
            c.timer.cancel();
            c.timer = null;
        }
        waitingForRun.remove(c);
        c.deadline = -1;
        Mutex m = mutexes.get(c.mutex);
        if (m == null) {
            release(c, ClockProtocol.ERROR);
        } else {
            lock(c, m, code);
        }
    }

    /** Blocks the thread serving {@code c} until its command may return; the reply. */
    private int awaitReply(Client c) throws IOException {
        synchronized (lock) {
            while (c.reply == null) {
                if (closed) {
                    throw new SocketException("the virtual clock server was closed");
                }
                try {
                    lock.wait(1000);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    throw new SocketException("interrupted");
                }
            }
            int reply = c.reply;
            c.reply = null;
            return reply;
        }
    }

    private void remove(Client c) {
        synchronized (lock) {
            clients.remove(c.id);
            waitingForRun.remove(c);
            if (c.timer != null) {
                c.timer.cancel();
            }
            for (List<Client> waiters : conditions.values()) {
                waiters.remove(c);
            }
            for (Mutex m : mutexes.values()) {
                m.queue.remove(c);
                if (m.owner == c) {
                    unlock(m);
                }
            }
            lock.notifyAll();
        }
    }

    /** Stops the server and ends every thread's connection. */
    @Override
    public void close() {
        closed = true;
        try {
            server.close();
        } catch (IOException e) {
            LOG.debug("closing the clock server: {}", e.getMessage());
        }
        List<Client> all;
        synchronized (lock) {
            all = new ArrayList<>(clients.values());
            lock.notifyAll();
        }
        for (Client c : all) {
            try {
                c.socket.close();
            } catch (IOException e) {
                LOG.debug("closing {}: {}", c, e.getMessage());
            }
        }
    }
}
