package io.dtron.testsupport;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.ArrayList;
import java.util.List;

/**
 * A TCP proxy on loopback that records what passes: it listens on a port, forwards every connection to a target
 * port on loopback, both ways, and keeps the bytes each client sent, as someone who can read the network's traffic
 * sees them. For replaying recorded traffic to the bus's members. Closing it closes every connection.
 */
public final class RecordingProxy implements AutoCloseable {
    private final ServerSocket server;
    private final int target;
    private final List<ByteArrayOutputStream> sent = new ArrayList<>();
    private final List<Socket> sockets = new ArrayList<>();

    /** Listens on {@code port} of loopback and forwards to {@code target} of loopback. */
    public RecordingProxy(int port, int target) throws IOException {
        this.server = new ServerSocket(port, 50, InetAddress.getLoopbackAddress());
        this.target = target;
        Thread acceptor = new Thread(this::accept, "recording-proxy-" + port);
        acceptor.setDaemon(true);
        acceptor.start();
    }

    private void accept() {
        while (!server.isClosed()) {
            try {
                Socket client = server.accept();
                Socket upstream = new Socket();
                try {
                    upstream.connect(new InetSocketAddress(InetAddress.getLoopbackAddress(), target), 2_000);
                } catch (IOException e) {
                    client.close(); // nothing listens there (yet)
                    continue;
                }
                ByteArrayOutputStream recording = new ByteArrayOutputStream();
                synchronized (this) {
                    sockets.add(client);
                    sockets.add(upstream);
                    sent.add(recording);
                }
                pump(client, upstream, recording);
                pump(upstream, client, null);
            } catch (IOException e) {
                // closed
            }
        }
    }

    private void pump(Socket from, Socket to, ByteArrayOutputStream recording) throws IOException {
        InputStream in = from.getInputStream();
        OutputStream out = to.getOutputStream();
        Thread thread = new Thread(() -> {
            byte[] buffer = new byte[8192];
            try {
                for (int n = in.read(buffer); n >= 0; n = in.read(buffer)) {
                    if (recording != null) {
                        synchronized (this) {
                            recording.write(buffer, 0, n);
                        }
                    }
                    out.write(buffer, 0, n);
                }
            } catch (IOException e) {
                // one side closed
            } finally {
                closeQuietly(from);
                closeQuietly(to);
            }
        }, "recording-proxy-pump");
        thread.setDaemon(true);
        thread.start();
    }

    /** Returns what each client sent so far, one array per connection, in the order they came. */
    public synchronized List<byte[]> recorded() {
        return sent.stream().map(ByteArrayOutputStream::toByteArray).toList();
    }

    private static void closeQuietly(Socket socket) {
        try {
            socket.close();
        } catch (IOException e) {
            // closed already
        }
    }

    @Override
    public synchronized void close() throws IOException {
        server.close();
        sockets.forEach(RecordingProxy::closeQuietly);
    }
}
