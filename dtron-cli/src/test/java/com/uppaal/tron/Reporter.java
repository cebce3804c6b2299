package com.uppaal.tron;

import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.Socket;
import java.nio.charset.StandardCharsets;

/**
 * The system under test's side of TRON's socket-adapter protocol, shaped like TRON's Java API: registers the
 * channels, their variables, the time unit and the timeout, starts the test, then (as a {@link VirtualThread}) reads
 * the tester's inputs and has the {@link Adapter} perform them, while {@link #report} sends outputs. In virtual time
 * it acknowledges every input after {@code perform} returns, and {@code report} returns only once the tester has
 * acknowledged the output, waiting on a plain monitor, so that the thread holds virtual time until then.
 */
public class Reporter extends VirtualThread {
    private static final int ACK = 0x8000_0000;

    private final Adapter adapter;
    private final DataInputStream in;
    private final DataOutputStream out;
    private final Object acks = new Object();
    private long outputsSent;
    private long outputsAcknowledged;
    private volatile boolean ended;

    /** A reporter for {@code adapter} over a connection to the tester. */
    public Reporter(Adapter adapter, Socket socket) throws IOException {
        super("reporter");
        this.adapter = adapter;
        socket.setTcpNoDelay(true);
        in = new DataInputStream(socket.getInputStream());
        out = new DataOutputStream(socket.getOutputStream());
    }

    /** Registers an input channel; its id. */
    public int getInputType(String name) {
        return checked(command(1, name, -1), "input " + name);
    }

    /** Registers an output channel; its id. */
    public int getOutputType(String name) {
        return checked(command(2, name, -1), "output " + name);
    }

    /** Attaches a global variable to an input channel. */
    public void addVarToInput(int channel, String variable) {
        checked(command(3, variable, channel), "variable " + variable);
    }

    /** Attaches a global variable to an output channel. */
    public void addVarToOutput(int channel, String variable) {
        checked(command(4, variable, channel), "variable " + variable);
    }

    /** Sets the model time unit, in microseconds (one int64, as TRON's Java client writes it). */
    public void setTimeUnit(long microseconds) {
        try {
            out.write(5);
            out.writeLong(microseconds);
            out.flush();
            checked(in.readInt(), "time unit");
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Sets the timeout, in model time units. */
    public void setTimeout(int units) {
        try {
            out.write(6);
            out.writeInt(units);
            out.flush();
            checked(in.readInt(), "timeout");
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /** Starts the test (the tester's reply comes when its run starts), then reads inputs on this thread. */
    @Override
    public synchronized void start() {
        try {
            out.write(64);
            out.flush();
            String reply = readString();
            if (!reply.isEmpty()) {
                throw new TronException("the tester refused the start: " + reply);
            }
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
        super.start();
    }

    /** Reports an output; in virtual time, returns when the tester has acknowledged it. */
    public void report(int channel, int... values) {
        long mine;
        synchronized (out) {
            try {
                out.writeInt(channel);
                out.writeShort(values.length);
                for (int v : values) {
                    out.writeInt(v);
                }
                out.flush();
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
            mine = ++outputsSent;
        }
        if (isVirtual()) {
            synchronized (acks) {
                while (outputsAcknowledged < mine && !ended) {
                    try {
                        acks.wait();
                    } catch (InterruptedException e) {
                        Thread.currentThread().interrupt();
                        return;
                    }
                }
            }
        }
    }

    @Override
    public void run() {
        try {
            while (true) {
                deactivate();
                int first = in.readInt();
                activate();
                if ((first & ACK) != 0) {
                    synchronized (acks) {
                        outputsAcknowledged += first & ~ACK;
                        acks.notifyAll();
                    }
                    continue;
                }
                int[] values = new int[in.readUnsignedShort()];
                for (int i = 0; i < values.length; i++) {
                    values[i] = in.readInt();
                }
                adapter.perform(first, values);
                if (isVirtual()) {
                    synchronized (out) {
                        out.writeInt(ACK | 1);
                        out.flush();
                    }
                }
            }
        } catch (EOFException e) {
            // the tester ended the test
        } catch (IOException | RuntimeException e) {
            System.out.println("reporter: " + e);
        } finally {
            ended = true;
            synchronized (acks) {
                acks.notifyAll();
            }
            quit();
        }
    }

    private int command(int code, String text, int channel) {
        try {
            byte[] bytes = text.getBytes(StandardCharsets.UTF_8);
            out.write(code);
            if (channel >= 0) {
                out.writeInt(channel);
            }
            out.write(bytes.length);
            out.write(bytes);
            out.flush();
            return in.readInt();
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private int checked(int result, String what) {
        if (result < 0) {
            try {
                out.write(127);
                out.writeInt(result);
                out.flush();
                throw new TronException(what + ": error " + result + ": " + readString());
            } catch (IOException e) {
                throw new UncheckedIOException(e);
            }
        }
        return result;
    }

    private String readString() throws IOException {
        byte[] bytes = new byte[in.readUnsignedByte()];
        in.readFully(bytes);
        return new String(bytes, StandardCharsets.UTF_8);
    }
}
