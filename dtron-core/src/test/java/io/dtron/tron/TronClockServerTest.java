package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.testsupport.Waits;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.EOFException;
import java.io.IOException;
import java.net.InetAddress;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * TRON's virtual clock server over real sockets, with hand-written clients: its mutexes and conditions, when the
 * adapter's threads count as blocked, and malformed commands. (Timed waits on a run's clock are tested end to end,
 * with TRON's smart-lamp sample, in the command line's tests.)
 */
@Timeout(value = 20, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronClockServerTest {

    /** One virtual thread's connection. */
    private static final class Client implements AutoCloseable {
        final Socket socket;
        final DataOutputStream out;
        final DataInputStream in;

        Client(TronClockServer server, String name) throws IOException {
            socket = new Socket(InetAddress.getLoopbackAddress(), server.port());
            socket.setSoTimeout(10_000);
            out = new DataOutputStream(socket.getOutputStream());
            in = new DataInputStream(socket.getInputStream());
            out.write(name.length());
            out.write(name.getBytes(StandardCharsets.US_ASCII));
            out.flush();
        }

        void send(int command, int... args) throws IOException {
            out.write(command);
            for (int a : args) {
                out.writeInt(a);
            }
            out.flush();
        }

        int call(int command, int... args) throws IOException {
            send(command, args);
            return in.readInt();
        }

        @Override
        public void close() throws IOException {
            socket.close();
        }
    }

    private static void awaitConnected(TronClockServer server, int n) {
        Waits.await(n + " threads connected").until(() -> server.threadsConnected() >= n);
        assertEquals(n, server.threadsConnected());
    }

    @Test
    void threadsHoldTimeUntilTheyBlockOnAMutexOrAConditionOrDeactivate() throws Exception {
        try (TronClockServer server = TronClockServer.open(InetAddress.getLoopbackAddress(), 0);
             Client a = new Client(server, "a"); Client b = new Client(server, "b")) {
            awaitConnected(server, 2);
            String both = server.awaitQuiet(Duration.ofMillis(50));
            assertTrue(both.contains("did not all block within 50 ms") && both.contains("'a'") && both.contains("'b'"),
                    both);
            assertEquals(0, a.call(1), "deactivate");
            assertTrue(server.awaitQuiet(Duration.ofMillis(50)).contains("still running: ['b']"));
            assertEquals(0, a.call(2), "activate");
            int mutex = a.call(3);
            int condition = a.call(7);
            assertTrue(mutex > 0 && condition > 0);
            assertEquals(0, a.call(5, mutex), "a locks");
            b.send(5, mutex); // b blocks on the mutex a holds
            assertTrue(server.awaitQuiet(Duration.ofMillis(50)).contains("still running: ['a']"),
                    "b is blocked, a runs");
            a.send(9, condition, mutex); // a waits, which hands the mutex to b
            assertEquals(0, b.in.readInt(), "b holds the mutex");
            assertTrue(server.awaitQuiet(Duration.ofMillis(50)).contains("still running: ['b']"));
            b.send(13, condition); // broadcast: a wakes, and waits for the mutex b holds
            assertEquals(0, b.call(1), "b deactivates");
            assertNull(server.awaitQuiet(Duration.ofMillis(500)), "a waits for the mutex, b is deactivated");
            assertEquals(0, b.call(2));
            assertEquals(0, b.call(6, mutex), "b unlocks");
            assertEquals(0, a.in.readInt(), "a's wait ends with the mutex held");
            assertEquals(64, b.call(6, mutex), "b no longer holds the mutex");
            b.send(14);
            assertEquals(0, b.in.readInt(), "before the run, time is 0 s");
            assertEquals(0, b.in.readInt(), "and 0 us");
        }
    }

    @Test
    void aMalformedCommandEndsThatThreadsConnectionAndIsCountedAndTheOthersGoOn() throws Exception {
        try (TronClockServer server = TronClockServer.open(InetAddress.getLoopbackAddress(), 0);
             Client rogue = new Client(server, "rogue"); Client careless = new Client(server, "careless")) {
            awaitConnected(server, 2);
            rogue.send(99);
            assertThrows(EOFException.class, rogue.in::readInt);
            careless.send(5, 777); // no such mutex
            assertThrows(EOFException.class, careless.in::readInt);
            assertEquals(2, server.rejected());
            try (Client next = new Client(server, "next")) {
                assertTrue(next.call(3) > 0, "the server still serves");
            }
        }
    }
}
