package io.dtron.tron;

import io.dtron.tron.internal.Wire;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.time.Duration;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;

/**
 * A test adapter written against the protocol, run in a JVM of its own: registers LightContr's interface with
 * {@link TronAdapterClient} and behaves like the lamp ({@link TronLamp}).
 *
 * <p>Arguments: {@code connect PORT | listen}, the time mode ({@code REAL_TIME}, {@code SHARED_VIRTUAL_CLOCK}), the
 * variant ({@code correct} or {@code late}), the timeout in units, the time unit in microseconds. When listening, it
 * prints {@code PORT n} first.
 * It prints {@code END} and the failure, if any, when the tester ends the test, and exits 0 (4 on a failure).
 */
public final class LampIutMain {
    private LampIutMain() {
    }

    public static void main(String[] args) throws IOException, InterruptedException {
        warmUp();
        TronAdapterClient.TimeMode mode = TronAdapterClient.TimeMode.valueOf(args[args.length - 4]);
        boolean late = args[args.length - 3].equals("late");
        int timeout = Integer.parseInt(args[args.length - 2]);
        int unit = Integer.parseInt(args[args.length - 1]);
        TronAdapterClient client;
        if (args[0].equals("listen")) {
            try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
                System.out.println("PORT " + server.getLocalPort());
                System.out.flush();
                client = TronAdapterClient.accept(server, mode);
            }
        } else {
            client = TronAdapterClient.connect("127.0.0.1", Integer.parseInt(args[1]), mode);
        }
        TronLamp.attach(client, unit, late, timeout);
        boolean ended = client.awaitEnd(Duration.ofSeconds(60));
        System.out.println("END " + (ended ? "" : "(timed out) ") + client.failure().orElse("")
                + " acknowledged=" + client.outputsAcknowledged());
        System.exit(client.failure().isPresent() || !ended ? 4 : 0);
    }

    /**
     * Runs the lamp's code paths once on a fast clock (a unit of 20 us), so that a cold JVM's class loading does not
     * make the first real-time outputs late.
     */
    private static void warmUp() throws InterruptedException {
        ScheduledExecutorService executor = Executors.newSingleThreadScheduledExecutor();
        long start = System.nanoTime();
        TestLamp lamp = new TestLamp(new TestLamp.Io() {
            @Override
            public long nowMicros() {
                return (System.nanoTime() - start) / 1000;
            }

            @Override
            public TestLamp.Cancel schedule(long micros, Runnable task) {
                ScheduledFuture<?> timer = executor.schedule(task, micros, TimeUnit.MICROSECONDS);
                return () -> timer.cancel(false);
            }

            @Override
            public void level(int value) {
                Wire.event(1, new int[] {value});
            }
        }, 20, false);
        for (int i = 0; i < 3; i++) {
            executor.execute(lamp::grasp);
            Thread.sleep(8);
            executor.execute(lamp::release);
            Thread.sleep(2);
        }
        executor.shutdown();
        executor.awaitTermination(1, TimeUnit.SECONDS);
    }
}
