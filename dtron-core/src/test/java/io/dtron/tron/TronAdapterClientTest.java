package io.dtron.tron;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.testsupport.OwnThreads;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.time.Duration;
import java.util.concurrent.ExecutionException;
import java.io.IOException;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** {@link TronAdapterClient} against DTRON's tester side ({@link TronSocketAdapter}) in one JVM, over real sockets. */
@Timeout(value = 30, unit = TimeUnit.SECONDS, threadMode = Timeout.ThreadMode.SEPARATE_THREAD)
class TronAdapterClientTest {
    /** The system answers every ping with a pong carrying the number of pings, within 2 units. */
    private static final String PING_PONG = """
            chan ping, pong, req[2];
            int count;
            bool flag;
            clock c;
            process Iut() { clock x; state Idle, Busy { x <= 2 }; init Idle;
                trans Idle -> Busy { sync ping?; assign x = 0, count = count + 1; },
                      Busy -> Idle { sync pong!; }; }
            process Env() { clock e; state Ready { e <= 20 }, Waiting; init Ready;
                trans Ready -> Waiting { guard e >= 10; sync ping!; assign e = 0; },
                      Waiting -> Ready { sync pong?; assign e = 0; }; }
            system Iut, Env;
            """;
    private static final TronSocketAdapter.Settings FAST = TronSocketAdapter.Settings.forRealTime()
            .withReplyTimeout(Duration.ofSeconds(2));

    private static Network pingPong;
    private ServerSocket server;

    @BeforeAll
    static void load() throws Exception {
        pingPong = ModelLoader.load("pingpong.xta", PING_PONG);
    }

    @BeforeEach
    void listen() throws Exception {
        server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress());
        server.setSoTimeout(10_000);
    }

    @AfterEach
    void close() throws Exception {
        server.close();
    }

    private interface ClientScript {
        void run(TronAdapterClient client) throws Exception;
    }

    private CompletableFuture<Void> client(TronAdapterClient.TimeMode mode, ClientScript script) {
        return CompletableFuture.runAsync(() -> {
            try (TronAdapterClient client = TronAdapterClient.connect("127.0.0.1", server.getLocalPort(), mode)) {
                script.run(client);
            } catch (Exception e) {
                throw new IllegalStateException(e);
            }
        }, OwnThreads.named("adapter-client"));
    }

    /** A reactive system in virtual time with TRON's acknowledgements: answers each ping before acknowledging it. */
    private TestResult reactivePingPong(int offset, long seed) throws Exception {
        CompletableFuture<Void> iut = client(TronAdapterClient.TimeMode.VIRTUAL_ACKS, c -> {
            int ping = c.registerInput("ping");
            int pong = c.registerOutput("pong");
            c.addOutputVariable(pong, "count");
            c.setTimeUnit(1000);
            c.setTimeout(500);
            int[] count = {0};
            c.start((channel, values) -> {
                assertEquals(ping, channel);
                c.reportOutput(pong, ++count[0] + offset);
            });
            assertTrue(c.awaitEnd(Duration.ofSeconds(20)));
            assertTrue(c.failure().isEmpty(), c.failure().toString());
            assertTrue(c.outputsAcknowledged() > 0);
        });
        TronSocketAdapter tester = TronSocketAdapter.accept(server, pingPong, FAST.withVirtualTime(true));
        assertFalse(tester.sharedVirtualClock());
        TestInterface ti = tester.testInterface();
        TestResult result = new OnlineTester(pingPong, ti, tester, new TestOptions(seed, ti.timeUnitMicros(),
                ti.timeout(), DelayPolicy.RANDOM, 0, true)).run();
        iut.get(20, TimeUnit.SECONDS);
        return result;
    }

    @Test
    void aReactiveSystemPassesInVirtualTimeWithAcknowledgements() throws Exception {
        TestResult result = reactivePingPong(0, 5);
        assertEquals(Verdict.PASSED, result.verdict(), result.explanation());
        assertTrue(result.inputs() >= 20 && result.outputs() == result.inputs(), result.statisticsLine());
        assertEquals(500_000, result.durationMicros());
    }

    @Test
    void aReactiveSystemWithWrongValuesFailsInVirtualTimeWithAcknowledgements() throws Exception {
        TestResult result = reactivePingPong(1, 5);
        assertEquals(Verdict.FAILED, result.verdict(), result.explanation());
        assertTrue(result.explanation().contains("pong(count=2)"), result.explanation());
    }

    @Test
    void refusalsAreThrownWithTheTestersExplanation() throws Exception {
        CompletableFuture<Void> iut = client(TronAdapterClient.TimeMode.REAL_TIME, c -> {
            TronProtocolException noChannel = assertThrows(TronProtocolException.class, () -> c.registerInput("pin"));
            assertEquals(-2, noChannel.errorCode());
            assertTrue(noChannel.getMessage().startsWith("the tester refused input 'pin' (error -2): input 'pin' is"
                    + " not a global channel of pingpong.xta; its global channels: ping, pong, req[0], req[1]"),
                    noChannel.getMessage());
            TronProtocolException array = assertThrows(TronProtocolException.class, () -> c.registerOutput("req"));
            assertTrue(array.getMessage().contains("'req' is a channel array: register its elements, e.g. 'req[0]'"),
                    array.getMessage());
            int req = c.registerOutput("req[1]");
            TronProtocolException clock = assertThrows(TronProtocolException.class,
                    () -> c.addOutputVariable(req, "c"));
            assertTrue(clock.getMessage().contains("it is a clock, not an int"), clock.getMessage());
            c.addOutputVariable(req, "flag");
            TronProtocolException start = assertThrows(TronProtocolException.class, () -> c.start((id, v) -> { }));
            assertTrue(start.getMessage().startsWith("the tester refused to start: 3 registrations were refused"),
                    start.getMessage());
        });
        TronProtocolException e = assertThrows(TronProtocolException.class,
                () -> TronSocketAdapter.accept(server, pingPong, FAST));
        assertTrue(e.getMessage().contains("3 registrations were refused"), e.getMessage());
        iut.get(10, TimeUnit.SECONDS);
    }

    @Test
    void channelArrayElementsAndBoolVariablesMakeTheInterface() throws Exception {
        CompletableFuture<Void> iut = client(TronAdapterClient.TimeMode.REAL_TIME, c -> {
            assertEquals(1, c.registerInput("ping"));
            int req = c.registerOutput("req[1]");
            c.addOutputVariable(req, "flag");
            c.addOutputVariable(req, "count");
            c.setTimeUnit(2_500_000);
            c.setTimeout(77);
            c.start((id, v) -> { });
        });
        TronSocketAdapter tester = TronSocketAdapter.accept(server, pingPong, FAST);
        TestInterface ti = tester.testInterface();
        assertEquals("ping", ti.inputs().get(0).name());
        TestInterface.ObservableChannel req = ti.outputs().get(0);
        assertEquals("req[1]", req.name());
        assertEquals(pingPong.channel("req").orElseThrow().index() + 1, req.channel());
        assertEquals(List.of("flag", "count"), req.variables().stream().map(TestInterface.AttachedVariable::name)
                .toList());
        assertEquals(2_500_000L, ti.timeUnitMicros());
        assertEquals(77L, ti.timeout());
        Thread.sleep(200);
        assertFalse(iut.isDone(), "the start is accepted only when the engine starts the run");
        tester.close();
        ExecutionException closed = assertThrows(ExecutionException.class, () -> iut.get(10, TimeUnit.SECONDS));
        assertInstanceOf(IOException.class, closed.getCause().getCause(), closed.toString());
    }

    @Test
    void theSharedVirtualClockIsRefusedInARealTimeRun() throws Exception {
        CompletableFuture<Void> iut = client(TronAdapterClient.TimeMode.SHARED_VIRTUAL_CLOCK, c -> {
            c.registerInput("ping");
            TronProtocolException e = assertThrows(TronProtocolException.class, () -> c.start((id, v) -> { }));
            assertEquals(-12, e.errorCode());
            assertTrue(e.getMessage().contains("the tester runs in real time"), e.getMessage());
        });
        assertThrows(TronProtocolException.class, () -> TronSocketAdapter.accept(server, pingPong, FAST));
        iut.get(10, TimeUnit.SECONDS);
    }

    @Test
    void theClientEndsWithAClearFailureWhenTheTesterSendsAnUnregisteredChannel() throws Exception {
        CompletableFuture<TronAdapterClient> iut = CompletableFuture.supplyAsync(() -> {
            try {
                TronAdapterClient c = TronAdapterClient.connect("127.0.0.1", server.getLocalPort(),
                        TronAdapterClient.TimeMode.REAL_TIME);
                c.registerInput("ping");
                c.start((id, v) -> { });
                assertTrue(c.awaitEnd(Duration.ofSeconds(10)));
                return c;
            } catch (Exception e) {
                throw new IllegalStateException(e);
            }
        });
        try (Socket tester = server.accept()) {
            DataInputStream in = new DataInputStream(tester.getInputStream());
            DataOutputStream out = new DataOutputStream(tester.getOutputStream());
            assertEquals(1, in.readUnsignedByte());
            assertEquals("ping", new String(in.readNBytes(in.readUnsignedByte()), "US-ASCII"));
            out.writeInt(1);
            assertEquals(64, in.readUnsignedByte());
            out.writeByte(0);
            out.writeInt(9);
            out.writeShort(0);
            out.flush();
            TronAdapterClient client = iut.get(10, TimeUnit.SECONDS);
            assertEquals("protocol error: the tester sent an event on channel id 9, which is not a registered input",
                    client.failure().orElseThrow());
            assertEquals(-1, in.read());
        }
    }
}
