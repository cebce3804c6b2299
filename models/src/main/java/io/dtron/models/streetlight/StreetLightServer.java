package io.dtron.models.streetlight;

import java.io.IOException;
import java.net.URI;
import java.net.http.HttpClient;
import java.time.Duration;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import org.eclipse.jetty.server.Server;
import org.eclipse.jetty.server.ServerConnector;
import org.eclipse.jetty.util.thread.QueuedThreadPool;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The street-light sample's system under test: a small web application on loopback (Jetty, an ephemeral port)
 * where operators {@code user0}, {@code user1}, ... (password {@value #PASSWORD}) log in, open the list of light
 * controllers, tick some, switch them on, off or to dimmed, and see on a result page whether each controller
 * reached the new state (OK), did not within 3 s (NOK, with the state it reports), or is still on its way
 * (PENDING). Simulated controllers poll the server every 100 ms with their status as a Base64 string and
 * converge to the state requested of them.
 *
 * <p>The session mix-up switch ({@code sessionMixUp}, or the system property
 * {@value #SESSION_MIX_UP_PROPERTY}{@code =true}) puts the bug of the case study in: what each operator works on
 * is kept in one place for all sessions, so that concurrent operators switch and see each other's controllers.
 * It is off by default.
 */
public final class StreetLightServer implements AutoCloseable {
    /** The system property that turns the session mix-up on for {@link #StreetLightServer(int)}. */
    public static final String SESSION_MIX_UP_PROPERTY = "streetlight.sessionMixUp";
    /** Every operator's password. */
    public static final String PASSWORD = "streetlight";

    private static final Logger LOG = LoggerFactory.getLogger(StreetLightServer.class);
    private static final Duration POLL_PERIOD = Duration.ofMillis(100);

    private final Controllers controllers;
    private final boolean sessionMixUp;
    private Server server;
    private ScheduledExecutorService pollers;
    private URI uri;

    /**
     * A server with {@code controllers} light controllers, with or without the session mix-up.
     *
     * @throws IllegalArgumentException if there is no controller
     */
    public StreetLightServer(int controllers, boolean sessionMixUp) {
        if (controllers < 1) {
            throw new IllegalArgumentException("the server needs at least one controller, not " + controllers);
        }
        this.controllers = new Controllers(controllers);
        this.sessionMixUp = sessionMixUp;
    }

    /** A server with the session mix-up as the system property {@value #SESSION_MIX_UP_PROPERTY} says. */
    public StreetLightServer(int controllers) {
        this(controllers, Boolean.getBoolean(SESSION_MIX_UP_PROPERTY));
    }

    /**
     * Starts the web application on 127.0.0.1 on a free port, and the controllers' polling.
     *
     * @return this server
     * @throws IOException           if the server cannot start
     * @throws IllegalStateException if it was started before
     */
    public synchronized StreetLightServer start() throws IOException {
        if (server != null) {
            throw new IllegalStateException("the street-light server starts once");
        }
        QueuedThreadPool threads = new QueuedThreadPool(32, 4);
        threads.setName("streetlight-http");
        threads.setDaemon(true);
        server = new Server(threads);
        ServerConnector connector = new ServerConnector(server, 1, 1);
        connector.setHost("127.0.0.1");
        connector.setPort(0);
        server.addConnector(connector);
        server.setHandler(new WebApp(controllers, sessionMixUp));
        try {
            server.start();
        } catch (Exception e) {
            close();
            throw new IOException("cannot start the street-light server: " + e.getMessage(), e);
        }
        uri = URI.create("http://127.0.0.1:" + connector.getLocalPort());
        HttpClient client = HttpClient.newBuilder().connectTimeout(Duration.ofSeconds(2)).build();
        pollers = Executors.newScheduledThreadPool(2, r -> {
            Thread t = new Thread(r, "streetlight-controllers");
            t.setDaemon(true);
            return t;
        });
        long period = POLL_PERIOD.toMillis();
        for (int id = 0; id < controllers.count(); id++) {
            VirtualController controller = new VirtualController(id, uri, client);
            pollers.scheduleWithFixedDelay(controller::poll, id * period / controllers.count(), period,
                    TimeUnit.MILLISECONDS);
        }
        LOG.info("Street-light server at {} with {} controllers{}", uri, controllers.count(),
                sessionMixUp ? ", session mix-up ON" : "");
        return this;
    }

    /**
     * Returns the address of the application, {@code http://127.0.0.1:PORT}.
     *
     * @throws IllegalStateException if the server is not started
     */
    public synchronized String url() {
        if (uri == null) {
            throw new IllegalStateException("the street-light server is not started");
        }
        return uri.toString();
    }

    /** Returns whether the session mix-up is on. */
    public boolean sessionMixUp() {
        return sessionMixUp;
    }

    /** Returns the number of light controllers. */
    public int controllers() {
        return controllers.count();
    }

    /** Stops the controllers and the server; closing twice does nothing. */
    @Override
    public synchronized void close() {
        if (pollers != null) {
            pollers.shutdownNow();
            pollers = null;
        }
        if (server != null) {
            try {
                server.stop();
            } catch (Exception e) {
                LOG.warn("The street-light server did not stop cleanly: {}", e.toString());
            }
        }
    }

    /**
     * Runs the application until the process is stopped: {@code [CONTROLLERS]} (default 8); the session mix-up
     * with {@code -D}{@value #SESSION_MIX_UP_PROPERTY}{@code =true}.
     */
    public static void main(String[] args) throws Exception {
        int count = args.length > 0 ? Integer.parseInt(args[0]) : 8;
        StreetLightServer server = new StreetLightServer(count).start();
        CountDownLatch stopped = new CountDownLatch(1);
        Runtime.getRuntime().addShutdownHook(new Thread(() -> {
            server.close();
            stopped.countDown();
        }));
        System.out.println("Street lights at " + server.url() + " (user0, user1, ... password " + PASSWORD
                + "); stop with Ctrl-C");
        stopped.await();
    }
}
