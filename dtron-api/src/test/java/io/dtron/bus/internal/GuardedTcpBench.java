package io.dtron.bus.internal;

import java.io.BufferedInputStream;
import java.io.DataInputStream;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.ByteBuffer;
import java.util.Arrays;

/**
 * What the guard of a JGroups bus costs one frame of 100 bytes (about a DTRON message), in this JVM, each part timed
 * alone after a warm-up: copying the frame and making its code for its place in its connection, as a sender does;
 * checking the code, as a receiver does; and reading the frame, already arrived, from a loopback socket as JGroups'
 * reader does (its length, then the frame), through a 64 KiB buffer (as GuardedTcp's connections are read) and
 * straight from the socket (five system calls instead of one). Prints count, p50, p99 and max in nanoseconds.
 * Argument (optional):
 * the number of frames (default 200,000; the socket reads take a tenth of it).
 */
public final class GuardedTcpBench {
    private static final int FRAME = 100;

    private GuardedTcpBench() {
    }

    public static void main(String[] args) throws IOException {
        int n = args.length > 0 ? Integer.parseInt(args[0]) : 200_000;
        byte[] key = BusKeys.macKey("0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef");
        byte[] data = new byte[FRAME];
        Arrays.fill(data, (byte) 7);
        for (int round = 0; round < 2; round++) { // the first is the warm-up
            byte[] openerNonce = new byte[GuardedTcp.NONCE_LENGTH];
            byte[] acceptorNonce = new byte[GuardedTcp.NONCE_LENGTH];
            acceptorNonce[0] = (byte) round;
            byte[] connectionKey = GuardedTcp.connectionKey(key, openerNonce, acceptorNonce);
            GuardedTcp.Link sender = new GuardedTcp.Link(connectionKey);
            GuardedTcp.Link receiver = new GuardedTcp.Link(connectionKey);
            long[] make = new long[n];
            long[] check = new long[n];
            for (int i = 0; i < n; i++) {
                long t0 = System.nanoTime();
                byte[] frame = Arrays.copyOf(data, FRAME + GuardedTcp.CODE_LENGTH);
                sender.code(frame, FRAME);
                long t1 = System.nanoTime();
                if (!receiver.check(frame, FRAME)) {
                    throw new IllegalStateException("a valid frame was dropped");
                }
                long t2 = System.nanoTime();
                make[i] = t1 - t0;
                check[i] = t2 - t1;
            }
            long[] direct = reads(n / 10, false);
            long[] buffered = reads(n / 10, true);
            if (round == 1) {
                System.out.println("copy and code a frame:      " + summary(make));
                System.out.println("check a frame's code:       " + summary(check));
                System.out.println("read a frame, unbuffered:   " + summary(direct));
                System.out.println("read a frame, 64 KiB buffer: " + summary(buffered));
            }
        }
    }

    /** Times reading {@code n} frames, each once it has arrived whole, from a loopback socket. */
    private static long[] reads(int n, boolean buffered) throws IOException {
        InetAddress loopback = InetAddress.getLoopbackAddress();
        try (ServerSocket server = new ServerSocket(0, 1, loopback);
                Socket client = new Socket(loopback, server.getLocalPort());
                Socket accepted = server.accept()) {
            client.setTcpNoDelay(true);
            OutputStream out = client.getOutputStream();
            InputStream raw = accepted.getInputStream();
            DataInputStream in = new DataInputStream(buffered ? new BufferedInputStream(raw, 65536) : raw);
            byte[] wire = ByteBuffer.allocate(4 + FRAME + GuardedTcp.CODE_LENGTH)
                    .putInt(FRAME + GuardedTcp.CODE_LENGTH).array();
            long[] nanos = new long[n];
            for (int i = 0; i < n; i++) {
                out.write(wire);
                out.flush();
                while (raw.available() < wire.length) {
                    Thread.onSpinWait(); // until the whole frame is in the socket's buffer
                }
                long t0 = System.nanoTime();
                int length = in.readInt();
                byte[] frame = new byte[length];
                in.readFully(frame);
                nanos[i] = System.nanoTime() - t0;
            }
            return nanos;
        }
    }

    private static String summary(long[] nanos) {
        long[] sorted = nanos.clone();
        Arrays.sort(sorted);
        return "count " + sorted.length + ", p50 " + sorted[sorted.length / 2] + " ns, p99 "
                + sorted[(int) (sorted.length * 0.99)] + " ns, max " + sorted[sorted.length - 1] + " ns";
    }
}
