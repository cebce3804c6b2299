package io.dtron.tron;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.ConnectException;
import java.time.Duration;

/** {@link TestLamp} behind a {@link TronAdapterClient}: in this JVM, or in a JVM of its own ({@link LampIutMain}). */
final class TronLamp {
    private TronLamp() {
    }

    /** Connects to the tester at {@code port}, registers LightContr's interface and runs the lamp to the end. */
    static void run(int port, TronAdapterClient.TimeMode mode, boolean late, int timeout) {
        try (TronAdapterClient client = TronAdapterClient.connect("127.0.0.1", port, mode)) {
            attach(client, 1000, late, timeout);
            client.awaitEnd(Duration.ofSeconds(60));
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /**
     * {@link #run} in shared virtual time with a timeout of 1000 units, against a tester that is about to listen on
     * {@code port}: a refused connection is tried again for up to 20 seconds.
     */
    static void runWhenListening(int port) throws InterruptedException {
        long deadline = System.nanoTime() + Duration.ofSeconds(20).toNanos();
        while (true) {
            try {
                run(port, TronAdapterClient.TimeMode.SHARED_VIRTUAL_CLOCK, false, 1000);
                return;
            } catch (UncheckedIOException e) {
                if (!(e.getCause().getCause() instanceof ConnectException) || System.nanoTime() > deadline) {
                    throw e;
                }
                Thread.sleep(50);
            }
        }
    }

    /**
     * Registers LightContr's interface (inputs grasp and release, output level with adapLevel), the time unit and
     * the timeout with {@code client}, and starts a lamp that takes its inputs and reports through it.
     */
    static void attach(TronAdapterClient client, int unit, boolean late, int timeout) throws IOException {
        int grasp = client.registerInput("grasp");
        int release = client.registerInput("release");
        int level = client.registerOutput("level");
        client.addOutputVariable(level, "adapLevel");
        client.setTimeUnit(unit);
        client.setTimeout(timeout);
        TestLamp lamp = new TestLamp(new TestLamp.Io() {
            @Override
            public long nowMicros() {
                return client.nowMicros();
            }

            @Override
            public TestLamp.Cancel schedule(long micros, Runnable task) {
                return client.schedule(micros, task)::cancel;
            }

            @Override
            public void level(int value) {
                client.reportOutput(level, value);
            }
        }, unit, late);
        client.start((channel, values) -> {
            if (channel == grasp) {
                lamp.grasp();
            } else if (channel == release) {
                lamp.release();
            }
        });
    }
}
