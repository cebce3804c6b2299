package io.dtron.tron;

import com.uppaal.tron.Adapter;
import com.uppaal.tron.Reporter;
import com.uppaal.tron.VirtualLock;
import com.uppaal.tron.VirtualThread;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.util.PriorityQueue;

/**
 * A smart lamp adapter written as TRON's Java sample is, against TRON's Java API shape (the {@code com.uppaal.tron}
 * fixture): its lamp runs on a {@link VirtualThread} with timed waits, it listens for the tester and registers through
 * a {@link Reporter} (output {@code level} twice, as TRON's sample does), and in virtual time it takes its time from
 * TRON's clock server, opening its port only after its threads have connected to the clock.
 *
 * <p>Arguments: {@code [-C HOST PORT] PORT VARIANT TIMEOUT UNIT}: the clock server (virtual time; without it, real
 * time), the port to listen on, {@code correct} or {@code late} ({@link TestLamp}), the timeout in units and the
 * time unit in microseconds. Prints {@code PORT n} when it listens and {@code END} when the tester has ended the test.
 */
public final class TronSampleLamp {
    private TronSampleLamp() {
    }

    /** The lamp's thread: runs its timers in time order, waiting for the next one on a virtual lock. */
    private static final class LampThread extends VirtualThread {
        private final VirtualLock lock = new VirtualLock();
        private final PriorityQueue<Timer> timers = new PriorityQueue<>();
        private long sequence;

        LampThread() {
            super("lamp");
            setDaemon(true);
        }

        Timer schedule(long micros, Runnable task) {
            lock.lock();
            try {
                Timer t = new Timer(VirtualThread.getTimeMicros() + micros, sequence++, task);
                timers.add(t);
                lock.signalAll();
                return t;
            } finally {
                lock.unlock();
            }
        }

        @Override
        public void run() {
            try {
                lock.lock();
                while (true) {
                    Timer next = timers.peek();
                    if (next == null) {
                        lock.await();
                        continue;
                    }
                    if (next.due > VirtualThread.getTimeMicros()) {
                        lock.awaitUntil(next.due);
                        continue;
                    }
                    timers.poll();
                    if (next.cancelled) {
                        continue;
                    }
                    lock.unlock();
                    next.task.run();
                    lock.lock();
                }
            } catch (InterruptedException | RuntimeException e) {
                // the clock or the tester ended the test
            }
        }
    }

    private static final class Timer implements Comparable<Timer>, TestLamp.Cancel {
        final long due;
        final long seq;
        final Runnable task;
        volatile boolean cancelled;

        Timer(long due, long seq, Runnable task) {
            this.due = due;
            this.seq = seq;
            this.task = task;
        }

        @Override
        public int compareTo(Timer o) {
            return due != o.due ? Long.compare(due, o.due) : Long.compare(seq, o.seq);
        }

        @Override
        public void cancel() {
            cancelled = true;
        }
    }

    public static void main(String[] args) throws Exception {
        int a = 0;
        if (args[0].equals("-C")) {
            VirtualThread.setClock(args[1], Integer.parseInt(args[2]));
            a = 3;
        }
        int port = Integer.parseInt(args[a]);
        boolean late = args[a + 1].equals("late");
        int timeout = Integer.parseInt(args[a + 2]);
        int unit = Integer.parseInt(args[a + 3]);
        LampThread thread = new LampThread();
        thread.start();
        Socket socket;
        try (ServerSocket server = new ServerSocket(port, 1, InetAddress.getLoopbackAddress())) {
            System.out.println("PORT " + server.getLocalPort());
            System.out.flush();
            socket = server.accept();
        }
        Reporter[] reporter = new Reporter[1];
        int[] ids = new int[3];
        TestLamp lamp = new TestLamp(new TestLamp.Io() {
            @Override
            public long nowMicros() {
                return VirtualThread.getTimeMicros();
            }

            @Override
            public TestLamp.Cancel schedule(long micros, Runnable task) {
                return thread.schedule(micros, task);
            }

            @Override
            public void level(int value) {
                reporter[0].report(ids[2], value);
            }
        }, unit, late);
        Adapter adapter = (channel, params) -> {
            if (channel == ids[0]) {
                lamp.grasp();
            } else if (channel == ids[1]) {
                lamp.release();
            }
        };
        reporter[0] = new Reporter(adapter, socket);
        ids[0] = reporter[0].getInputType("grasp");
        ids[1] = reporter[0].getInputType("release");
        ids[2] = reporter[0].getOutputType("level");
        if (reporter[0].getOutputType("level") != ids[2]) {
            System.out.println("level registered twice got another id");
            System.exit(4);
        }
        reporter[0].addVarToOutput(ids[2], "adapLevel");
        reporter[0].setTimeUnit(unit);
        reporter[0].setTimeout(timeout);
        reporter[0].start();
        reporter[0].join();
        System.out.println("END");
        System.exit(0);
    }
}
