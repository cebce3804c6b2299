package io.dtron.tron;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.time.Duration;

/** {@link TestLamp} behind a {@link TronAdapterClient} in this JVM, for tests that need no second process. */
final class InJvmLamp {
    private InJvmLamp() {
    }

    /** Connects to the tester at {@code port}, registers LightContr's interface and runs the lamp to the end. */
    static void run(int port, TronAdapterClient.TimeMode mode, boolean late, int timeout) {
        try (TronAdapterClient client = TronAdapterClient.connect("127.0.0.1", port, mode)) {
            int grasp = client.registerInput("grasp");
            client.registerInput("release");
            int level = client.registerOutput("level");
            client.addOutputVariable(level, "adapLevel");
            client.setTimeUnit(1000);
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
            }, 1000, late);
            client.start((channel, values) -> {
                if (channel == grasp) {
                    lamp.grasp();
                } else {
                    lamp.release();
                }
            });
            client.awaitEnd(Duration.ofSeconds(60));
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
