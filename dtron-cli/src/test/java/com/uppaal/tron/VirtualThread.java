package com.uppaal.tron;

import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.ConnectException;
import java.net.Socket;
import java.nio.charset.StandardCharsets;

/**
 * A thread that takes part in virtual time, shaped like TRON's Java API: with a clock server set ({@link #setClock},
 * an adapter's {@code -C HOST PORT}) each started thread opens its own connection to the server (tried 10 times, 2 s
 * apart) and takes its time, locks and waits from it; without one, it is a plain thread on the wall clock.
 */
public class VirtualThread extends Thread {
    private static volatile String clockHost;
    private static volatile int clockPort;
    private static final long WALL_START = System.nanoTime();

    private Socket clock;
    private DataOutputStream out;
    private DataInputStream in;

    /** A thread named {@code name}. */
    public VirtualThread(String name) {
        super(name);
    }

    /** Makes the threads started from now on use the clock server at {@code host:port}: virtual time. */
    public static void setClock(String host, int port) {
        clockHost = host;
        clockPort = port;
    }

    /** Whether threads use a clock server. */
    public static boolean isVirtual() {
        return clockHost != null;
    }

    /** Connects to the clock server (in virtual time), then starts the thread. */
    @Override
    public synchronized void start() {
        if (isVirtual()) {
            try {
                connect();
            } catch (IOException e) {
                throw new UncheckedIOException("cannot connect to the virtual clock at " + clockHost + ":"
                        + clockPort, e);
            }
        }
        super.start();
    }

    private void connect() throws IOException {
        for (int attempt = 1; ; attempt++) {
            try {
                clock = new Socket(clockHost, clockPort);
                break;
            } catch (ConnectException e) {
                if (attempt == 10) {
                    throw e;
                }
                try {
                    Thread.sleep(2000);
                } catch (InterruptedException ie) {
                    Thread.currentThread().interrupt();
                    throw e;
                }
            }
        }
        clock.setTcpNoDelay(true);
        out = new DataOutputStream(clock.getOutputStream());
        in = new DataInputStream(clock.getInputStream());
        byte[] name = getName().getBytes(StandardCharsets.UTF_8);
        out.write(name.length);
        out.write(name);
        out.flush();
    }

    /** The current virtual thread; in virtual time every caller of the clock must be one. */
    static VirtualThread current() {
        Thread t = Thread.currentThread();
        if (!(t instanceof VirtualThread)) {
            throw new IllegalStateException(t.getName() + " is not a VirtualThread and cannot use virtual time");
        }
        return (VirtualThread) t;
    }

    /** Sends a command with int32 arguments and reads {@code replies} int32 replies. */
    synchronized int[] call(int command, int replies, int... args) {
        try {
            out.write(command);
            for (int a : args) {
                out.writeInt(a);
            }
            out.flush();
            int[] result = new int[replies];
            for (int i = 0; i < replies; i++) {
                result[i] = in.readInt();
            }
            return result;
        } catch (IOException e) {
            throw new UncheckedIOException("the virtual clock connection of " + getName() + " failed", e);
        }
    }

    /**
     * The time in microseconds (TRON's API has it in milliseconds, {@code getTimeMillis}; the lamp needs finer): the
     * clock server's in virtual time, else since this class was loaded.
     */
    public static long getTimeMicros() {
        if (!isVirtual()) {
            return (System.nanoTime() - WALL_START) / 1000;
        }
        int[] t = current().call(14, 2);
        return t[0] * 1_000_000L + t[1];
    }

    /** Before blocking outside the clock's knowledge (a socket read): the thread no longer holds time back. */
    protected void deactivate() {
        if (isVirtual()) {
            call(1, 1);
        }
    }

    /** After such a block: the thread takes part in virtual time again. */
    protected void activate() {
        if (isVirtual()) {
            call(2, 1);
        }
    }

    /** Ends this thread's connection to the clock; call it when the thread's work is done. */
    protected void quit() {
        if (clock != null) {
            try {
                synchronized (this) {
                    out.write(127);
                    out.flush();
                }
                clock.close();
            } catch (IOException e) {
                // the server is gone already
            }
        }
    }
}
