package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.Verdict;
import io.dtron.model.Network;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

/**
 * Runs the tester's code paths once in virtual time before a real-time test, so that class loading in a cold JVM
 * does not make the tester's first inputs late.
 */
final class Warmup {
    private static boolean done;

    private Warmup() {
    }

    /** A short in-JVM run of the lamp over a real socket with the shared virtual clock (once per JVM). */
    static synchronized void lightContr(Network lightContr) throws Exception {
        if (done) {
            return;
        }
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            server.setSoTimeout(30_000);
            CompletableFuture<Void> lamp = CompletableFuture.runAsync(() -> TronLamp.run(server.getLocalPort(),
                    TronAdapterClient.TimeMode.SHARED_VIRTUAL_CLOCK, false, 2000));
            TronSocketAdapter adapter = TronSocketAdapter.accept(server, lightContr,
                    TronSocketAdapter.Settings.forVirtualTime());
            TestOptions options = new TestOptions(1, 1000, 2000, DelayPolicy.RANDOM, 0, true);
            assertEquals(Verdict.PASSED, new OnlineTester(lightContr, adapter.testInterface(), adapter, options).run()
                    .verdict());
            lamp.get(30, TimeUnit.SECONDS);
        }
        done = true;
    }
}
