package io.dtron.report;

import com.sun.net.httpserver.HttpExchange;
import com.sun.net.httpserver.HttpServer;
import io.dtron.report.internal.LiveClient;
import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.nio.charset.StandardCharsets;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The live view: serves the report page of a run while it goes on ({@code /}), the run's data ({@code /state.json})
 * and its updates as server-sent events ({@code /events}). Watching never slows the run: each browser has a
 * bounded queue that the run's thread fills without waiting; a browser that does not keep up loses updates (its page
 * then fetches the whole state again), never the run's events. Binds where it is told (the command line's default
 * is loopback).
 */
public final class LiveView implements AutoCloseable {
    /** How many browsers may follow a run at once; more are answered 503. */
    public static final int MAX_BROWSERS = 16;
    private static final Logger LOG = LoggerFactory.getLogger(LiveView.class);

    private final RunRecord record;
    private final HttpServer server;
    private final ExecutorService threads;
    private final List<LiveClient> clients = new CopyOnWriteArrayList<>();
    private final List<LiveClient> ended = new CopyOnWriteArrayList<>();
    private volatile boolean closed;

    private LiveView(RunRecord record, HttpServer server, ExecutorService threads) {
        this.record = record;
        this.server = server;
        this.threads = threads;
    }

    /**
     * Serves {@code record} on {@code address}:{@code port} (0: any free port) and follows its updates.
     *
     * @throws IOException if the port cannot be bound
     */
    public static LiveView start(RunRecord record, InetAddress address, int port) throws IOException {
        HttpServer server = HttpServer.create(new InetSocketAddress(address, port), 16);
        AtomicInteger n = new AtomicInteger();
        ExecutorService threads = Executors.newCachedThreadPool(r -> {
            Thread t = new Thread(r, "dtron-live-" + n.incrementAndGet());
            t.setDaemon(true);
            return t;
        });
        LiveView view = new LiveView(record, server, threads);
        server.setExecutor(threads);
        server.createContext("/", view::page);
        server.createContext("/state.json", view::state);
        server.createContext("/events", view::events);
        record.onUpdate(view::broadcast);
        server.start();
        return view;
    }

    /** The port it listens on. */
    public int port() {
        return server.getAddress().getPort();
    }

    /** The address it listens on, as {@code http://HOST:PORT/}. */
    public String url() {
        InetSocketAddress a = server.getAddress();
        String host = a.getAddress().getHostAddress();
        return "http://" + (host.contains(":") ? "[" + host + "]" : host) + ":" + a.getPort() + "/";
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

    private void page(HttpExchange exchange) throws IOException {
        if (!exchange.getRequestURI().getPath().equals("/")) {
            send(exchange, 404, "text/plain", "not found");
            return;
        }
        send(exchange, 200, "text/html; charset=utf-8", ReportPage.live());
    }

    private void state(HttpExchange exchange) throws IOException {
        send(exchange, 200, "application/json", record.json());
    }

    private void events(HttpExchange exchange) throws IOException {
        if (closed || clients.size() >= MAX_BROWSERS) {
            send(exchange, 503, "text/plain", closed ? "the run is over" : "too many browsers follow this run");
            return;
        }
        LiveClient client = new LiveClient();
        clients.add(client);
        try {
            exchange.getResponseHeaders().set("Content-Type", "text/event-stream");
            exchange.getResponseHeaders().set("Cache-Control", "no-cache");
            exchange.sendResponseHeaders(200, 0);
            try (OutputStream out = exchange.getResponseBody()) {
                client.stream(out);
            }
        } catch (IOException e) {
            LOG.debug("a browser of the live view went away: {}", e.toString());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } finally {
            clients.remove(client);
            ended.add(client);
            exchange.close();
        }
    }

    private static void send(HttpExchange exchange, int status, String type, String body) throws IOException {
        byte[] bytes = body.getBytes(StandardCharsets.UTF_8);
        exchange.getResponseHeaders().set("Content-Type", type);
        exchange.getResponseHeaders().set("Cache-Control", "no-cache");
        exchange.sendResponseHeaders(status, bytes.length);
        try (OutputStream out = exchange.getResponseBody()) {
            out.write(bytes);
        }
    }

    /**
     * Ends the browsers' streams after what they have queued (waiting up to a second for them to read it) and stops
     * serving.
     */
    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        record.onUpdate(null);
        for (LiveClient c : clients) {
            c.end();
        }
        // the streams end once the browsers have read what was queued; a browser that stopped reading is cut off
        threads.shutdown();
        try {
            threads.awaitTermination(1, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        server.stop(0);
        threads.shutdownNow();
    }
}
