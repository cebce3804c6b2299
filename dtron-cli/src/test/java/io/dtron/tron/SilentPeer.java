package io.dtron.tron;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

/** A peer on a loopback port that accepts one connection and says nothing: no TRON adapter. */
final class SilentPeer implements AutoCloseable {
    private final ServerSocket server;
    private final CompletableFuture<Void> peer;

    SilentPeer() throws IOException {
        server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress());
        peer = CompletableFuture.runAsync(() -> {
            try (var socket = server.accept()) {
                socket.getInputStream().read(); // silent until the tester gives up
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
        });
    }

    /** Its port. */
    int port() {
        return server.getLocalPort();
    }

    /** Waits until the tester has closed the connection. */
    void awaitHangUp() throws Exception {
        peer.get(10, TimeUnit.SECONDS);
    }

    @Override
    public void close() throws IOException {
        server.close();
    }
}
