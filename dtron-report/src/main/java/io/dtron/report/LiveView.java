package io.dtron.report;

import io.dtron.report.internal.HttpRequestLine;
import io.dtron.report.internal.LiveClient;
import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.util.List;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.SynchronousQueue;
import java.util.concurrent.ThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The live view: serves the report page of a run while it goes on ({@code /}), the run's data ({@code /state.json})
 * and its updates as server-sent events ({@code /events}). Watching never slows the run: each browser has a
 * bounded queue that the run's thread fills without waiting, and a bounded socket buffer; a browser that does not
 * keep up loses updates (its page then fetches the whole state again), never the run's events. Binds where it is
 * told (the command line's default is loopback).
 */
public final class LiveView implements AutoCloseable {
    /** How many browsers may follow a run at once; more are answered 503. */
    public static final int MAX_BROWSERS = 16;
    /** The socket send buffer of each browser's connection: with the queue, what a browser may be behind. */
    static final int SEND_BUFFER = 64 * 1024;
    private static final int READ_TIMEOUT_MILLIS = 10_000;
    private static final Logger LOG = LoggerFactory.getLogger(LiveView.class);

    private final RunRecord record;
    private final ServerSocket server;
    private final int queue;
    private final ThreadPoolExecutor threads;
    private final List<LiveClient> clients = new CopyOnWriteArrayList<>();
    private final List<LiveClient> ended = new CopyOnWriteArrayList<>();
    private final Set<Socket> sockets = ConcurrentHashMap.newKeySet();
    private volatile boolean closed;

    private LiveView(RunRecord record, ServerSocket server, int queue) {
        this.record = record;
        this.server = server;
        this.queue = queue;
        AtomicInteger n = new AtomicInteger();
        this.threads = new ThreadPoolExecutor(0, MAX_BROWSERS + 4, 30, TimeUnit.SECONDS, new SynchronousQueue<>(),
                r -> {
                    Thread t = new Thread(r, "dtron-live-" + n.incrementAndGet());
                    t.setDaemon(true);
                    return t;
                });
    }

    /**
     * Serves {@code record} on {@code address}:{@code port} (0: any free port) and follows its updates.
     *
     * @throws IOException if the port cannot be bound
     */
    public static LiveView start(RunRecord record, InetAddress address, int port) throws IOException {
        return start(record, address, port, LiveClient.QUEUE);
    }

    /** As {@link #start(RunRecord, InetAddress, int)}, with {@code queue} updates per browser at most. */
    static LiveView start(RunRecord record, InetAddress address, int port, int queue) throws IOException {
        ServerSocket server = new ServerSocket();
        try {
            server.bind(new InetSocketAddress(address, port), 50);
        } catch (IOException e) {
            server.close();
            throw e;
        }
        LiveView view = new LiveView(record, server, queue);
        record.onUpdate(view::broadcast);
        Thread acceptor = new Thread(view::accept, "dtron-live-accept");
        acceptor.setDaemon(true);
        acceptor.start();
        return view;
    }

    /** The port it listens on. */
    public int port() {
        return server.getLocalPort();
    }

    /** Where to open it: {@code http://HOST:PORT/}. */
    public String url() {
        String host = server.getInetAddress().getHostAddress();
        return "http://" + (host.contains(":") ? "[" + host + "]" : host) + ":" + port() + "/";
    }

    /** How many updates the browsers lost, all together, because they did not read them in time. */
    public long droppedUpdates() {
        long sum = 0;
        for (LiveClient c : clients) {
            sum += c.dropped();
        }
        for (LiveClient c : ended) {
            sum += c.dropped();
        }
        return sum;
    }

    /** How many browsers follow the run now. */
    public int browsers() {
        return clients.size();
    }

    /** Called on the run's thread for every update: queues it for each browser, never waiting. */
    private void broadcast(String update) {
        for (LiveClient c : clients) {
            c.offer(update);
        }
    }

    private void accept() {
        while (!closed) {
            Socket socket;
            try {
                socket = server.accept();
            } catch (IOException e) {
                if (!closed) {
                    LOG.warn("the live view stopped accepting browsers: {}", e.toString());
                }
                return;
            }
            try {
                socket.setSendBufferSize(SEND_BUFFER);
                socket.setSoTimeout(READ_TIMEOUT_MILLIS);
                sockets.add(socket);
                threads.execute(() -> serve(socket));
            } catch (RejectedExecutionException | IOException e) {
                refuse(socket);
            }
        }
    }

    private void refuse(Socket socket) {
        try (socket) {
            respond(socket.getOutputStream(), "503 Service Unavailable", "text/plain",
                    "too many browsers follow this run");
        } catch (IOException e) {
            LOG.debug("a refused browser went away: {}", e.toString());
        } finally {
            sockets.remove(socket);
        }
    }

    private void serve(Socket socket) {
        try (socket) {
            String path = HttpRequestLine.read(new java.io.BufferedInputStream(socket.getInputStream()));
            OutputStream out = socket.getOutputStream();
            switch (path == null ? "" : path) {
                case "/" -> respond(out, "200 OK", "text/html; charset=utf-8", ReportPage.live());
                case "/state.json" -> respond(out, "200 OK", "application/json", record.json());
                case "/events" -> events(out);
                default -> respond(out, path == null ? "400 Bad Request" : "404 Not Found", "text/plain",
                        path == null ? "not a GET request" : "not found");
            }
        } catch (IOException e) {
            LOG.debug("a browser of the live view went away: {}", e.toString());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } finally {
            sockets.remove(socket);
        }
    }

    private void events(OutputStream out) throws IOException, InterruptedException {
        if (closed || clients.size() >= MAX_BROWSERS) {
            respond(out, "503 Service Unavailable", "text/plain", closed ? "the run is over"
                    : "too many browsers follow this run");
            return;
        }
        LiveClient client = new LiveClient(queue);
        clients.add(client);
        try {
            out.write(("HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-cache\r\n"
                    + "Connection: close\r\n\r\n").getBytes(StandardCharsets.US_ASCII));
            client.stream(out);
        } finally {
            clients.remove(client);
            ended.add(client);
        }
    }

    private static void respond(OutputStream out, String status, String type, String body) throws IOException {
        byte[] bytes = body.getBytes(StandardCharsets.UTF_8);
        out.write(("HTTP/1.1 " + status + "\r\nContent-Type: " + type + "\r\nContent-Length: " + bytes.length
                + "\r\nCache-Control: no-cache\r\nConnection: close\r\n\r\n").getBytes(StandardCharsets.US_ASCII));
        out.write(bytes);
        out.flush();
    }

    /**
     * Ends the browsers' streams after what they have queued (waiting up to a second for them to read it) and stops
     * serving; a browser that stopped reading is cut off.
     */
    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        record.onUpdate(null);
        try {
            server.close();
        } catch (IOException e) {
            LOG.debug("closing the live view's socket: {}", e.toString());
        }
        for (LiveClient c : clients) {
            c.end();
        }
        threads.shutdown();
        try {
            threads.awaitTermination(1, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        for (Socket s : sockets) {
            try {
                s.close();
            } catch (IOException e) {
                LOG.debug("closing a browser's socket: {}", e.toString());
            }
        }
        threads.shutdownNow();
    }
}
