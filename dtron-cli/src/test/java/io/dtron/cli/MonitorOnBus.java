package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.testsupport.Waits;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.stream.Stream;

/**
 * {@code dtron monitor} of the monitor tests' server model ({@link MonitorCommandTest#SERVER}) on a JGroups bus of
 * its own on loopback, run on a thread of its own, for tests whose real members play the run's tester and system.
 */
final class MonitorOnBus {
    /** The model's request, an input of the system, and its response, an output. */
    static final IDtronChannel REQ = IDtronChannel.of("req", "n");
    static final IDtronChannel RESP = IDtronChannel.of("resp", "n");
    /** The time unit the tests' runs announce (100 ms), in nanoseconds. */
    static final long UNIT_NANOS = 100_000_000L;
    final StringWriter out = new StringWriter();
    final StringWriter err = new StringWriter();
    /** The bus's name: {@code prefix} and a random suffix. */
    final String cluster;
    private final Path model;
    private CompletableFuture<Integer> exit;

    /** Copies the model into {@code dir}; nothing runs yet. */
    MonitorOnBus(Path dir, String prefix) throws IOException {
        model = dir.resolve("server.xta");
        Files.copy(MonitorCommandTest.SERVER, model);
        cluster = prefix + "-" + UUID.randomUUID().toString().substring(0, 8);
    }

    /** A member of the bus, bound to loopback. */
    Dtron member() {
        return Dtron.connect(DtronOptions.builder().clusterName(cluster).bindAddress(InetAddress.getLoopbackAddress())
                .build());
    }

    /**
     * Starts the monitor, with {@code options} after the model and bus, and waits until it is on the bus, one of
     * {@code members} that {@code member} sees.
     */
    void start(Dtron member, int members, String... options) {
        String[] args = Stream.concat(Stream.of("monitor", model.toString(), "--cluster", cluster),
                Stream.of(options)).toArray(String[]::new);
        exit = CompletableFuture.supplyAsync(() -> DtronCommand.run(args, new PrintWriter(out, true),
                new PrintWriter(err, true)));
        Waits.await("the monitor on the bus").until(() -> out.toString().contains(" as ") || exit.isDone());
        Waits.await("the monitor among the members").until(() -> member.getMembers().size() == members);
    }

    /** The monitor's exit code, once it ended (at most a minute from now). */
    int exit() throws Exception {
        return exit.get(1, TimeUnit.MINUTES);
    }

    /** What the monitor printed, its output and then its errors. */
    String shown() {
        return out + "\n" + err;
    }
}
