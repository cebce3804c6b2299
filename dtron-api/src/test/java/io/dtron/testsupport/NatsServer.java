package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.fail;

import java.io.File;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.TimeUnit;
import java.util.regex.Pattern;

/**
 * A {@code nats-server} with JetStream, started by a test on a free loopback port with a store in a folder of the
 * test's: alone, or as one of a cluster. A test that needs it is skipped when no {@code nats-server} is installed,
 * unless the environment says {@code DTRON_REQUIRE_TOOLS=1} (as scripts/test does): then it fails.
 */
public final class NatsServer implements AutoCloseable {
    private final Process process;
    private final int port;
    private final Path log;

    private NatsServer(Process process, int port, Path log) {
        this.process = process;
        this.port = port;
        this.log = log;
    }

    /** Returns {@code nats-server} on the PATH or in /usr/sbin, if installed. */
    public static Optional<Path> executable() {
        List<String> dirs = new ArrayList<>(List.of(System.getenv().getOrDefault("PATH", "").split(File.pathSeparator)));
        dirs.add("/usr/sbin");
        return dirs.stream().filter(d -> !d.isEmpty()).map(d -> Path.of(d, "nats-server")).filter(Files::isExecutable)
                .findFirst();
    }

    /** Skips the calling test when a tool is missing, or fails it under {@code DTRON_REQUIRE_TOOLS=1} ({@link Tools}). */
    public static void requireTool(boolean present, String what) {
        Tools.require(present, what);
    }

    /** Returns a port that was free on loopback a moment ago. */
    public static int freePort() throws IOException {
        try (ServerSocket socket = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            return socket.getLocalPort();
        }
    }

    /** Starts a single server with JetStream, its store and log in {@code dir}. */
    public static NatsServer start(Path dir) throws IOException, InterruptedException {
        return start(dir, "n", freePort(), List.of());
    }

    /** Starts a single server with JetStream and more options of nats-server's ({@code --user}, {@code --pass}). */
    public static NatsServer startWith(Path dir, List<String> options) throws IOException, InterruptedException {
        return start(dir, "n", freePort(), options);
    }

    /**
     * Starts a server with JetStream on {@code port}, its store and log in {@code dir}: alone when {@code routes} is
     * empty, else as server {@code name} of the cluster {@code dtron-test} listening for routes on {@code
     * clusterPort} and routing to the others' cluster ports.
     */
    public static NatsServer startClustered(Path dir, String name, int port, int clusterPort, List<Integer> routes)
            throws IOException, InterruptedException {
        List<String> args = new ArrayList<>(List.of("--cluster_name", "dtron-test", "--cluster",
                "nats://127.0.0.1:" + clusterPort, "--routes", String.join(",", routes.stream()
                        .map(p -> "nats://127.0.0.1:" + p).toList())));
        return start(dir, name, port, args);
    }

    private static NatsServer start(Path dir, String name, int port, List<String> extra)
            throws IOException, InterruptedException {
        Optional<Path> binary = executable();
        requireTool(binary.isPresent(), "nats-server");
        Path store = Files.createDirectories(dir.resolve("nats-" + name));
        Path log = store.resolve("server.log");
        List<String> command = new ArrayList<>(List.of(binary.get().toString(), "-n", name, "-a", "127.0.0.1",
                "-p", Integer.toString(port), "-js", "-sd", store.toString()));
        command.addAll(extra);
        Process process = new ProcessBuilder(command).redirectErrorStream(true).redirectOutput(log.toFile()).start();
        NatsServer server = new NatsServer(process, port, log);
        server.awaitLog("Server is ready", Duration.ofSeconds(30));
        return server;
    }

    /** Waits until the server's log shows {@code text}; fails the test if it exits first or the timeout passes. */
    public void awaitLog(String text, Duration timeout) {
        try {
            Waits.awaitOutput(process, log, Pattern.compile(Pattern.quote(text)), timeout);
        } catch (AssertionError e) {
            process.destroyForcibly();
            throw e;
        }
    }

    /** Returns the server's client URL, {@code nats://127.0.0.1:PORT}. */
    public String url() {
        return "nats://127.0.0.1:" + port;
    }

    /** Returns the server's log so far. */
    public String log() throws IOException {
        return Files.readString(log);
    }

    /** Kills the server at once, as a crash would. */
    public void kill() throws InterruptedException {
        process.destroyForcibly();
        process.waitFor(10, TimeUnit.SECONDS);
    }

    @Override
    public void close() throws InterruptedException {
        if (process.isAlive()) {
            process.destroy();
            if (!process.waitFor(5, TimeUnit.SECONDS)) {
                kill();
            }
        }
    }
}
