package io.dtron.tron;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestClock;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.TestInterface;
import io.dtron.tron.internal.Wire;
import io.dtron.troninstaller.RunningTron;
import io.dtron.troninstaller.TronArguments;
import io.dtron.troninstaller.TronInstallation;
import io.dtron.troninstaller.TronLauncher;
import io.dtron.troninstaller.TronNotFoundException;
import io.dtron.troninstaller.TronOutput;
import java.io.IOException;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.atomic.AtomicInteger;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * An installed Uppaal TRON as DTRON's backend ({@code dtron run MODEL --backend tron}): DTRON listens on loopback,
 * launches {@code tron -I SocketAdapter [-P ..] -F TIMEOUT -X SEED MODEL -- 127.0.0.1 PORT} with commons-exec, takes
 * the adapter's side of the protocol ({@link TronAdapterClient}) with the interface of the run, and bridges TRON's
 * inputs to the system under test and its outputs back, exactly as the embedded engine drives an {@link Adapter}.
 * TRON's verdict and seed are read from its output ({@link TronOutput}, an assumed format) or, failing that, from its
 * exit code (0, 2, 3), and become the run's {@link TestResult}. Real time only.
 */
public final class TronBackend {
    private static final Logger LOG = LoggerFactory.getLogger(TronBackend.class);
    private static final Duration CONNECT_TIMEOUT = Duration.ofSeconds(60);
    private static final Duration GRACE = Duration.ofSeconds(60);

    private final TronLauncher launcher;
    private final OutputStream echo;

    /** A backend that launches TRON with {@code launcher} and echoes TRON's output to {@code echo} (or nowhere). */
    public TronBackend(TronLauncher launcher, OutputStream echo) {
        this.launcher = Objects.requireNonNull(launcher, "launcher");
        this.echo = echo;
    }

    /**
     * The backend of the TRON found by {@code installation}.
     *
     * @throws TronNotFoundException when TRON is not installed; the message says what to do
     */
    public static TronBackend installed(TronInstallation installation, OutputStream echo)
            throws TronNotFoundException {
        return new TronBackend(TronLauncher.installed(installation), echo);
    }

    /** TRON's {@code -P} value for a delay policy. */
    static String delayArgument(TestOptions options) {
        switch (options.delayPolicy()) {
            case EAGER: return "eager";
            case LAZY: return "lazy";
            case RANDOM_BOUNDED: return "0," + options.delayBound();
            default: return "random";
        }
    }

    /**
     * Tests {@code sut} against {@code model} with TRON, in real time.
     *
     * @throws IllegalArgumentException when the options ask for virtual time
     * @throws IOException              when TRON cannot be started, does not connect, breaks the protocol or prints
     *                                  no verdict
     */
    public TestResult run(Path model, TestInterface testInterface, Adapter sut, TestOptions options)
            throws IOException, InterruptedException {
        if (options.virtualTime()) {
            throw new IllegalArgumentException("the TRON backend runs in real time only; leave out virtual time, or"
                    + " use DTRON's own engine");
        }
        if (options.timeout() > Integer.MAX_VALUE) {
            throw new IllegalArgumentException("TRON's timeout is at most " + Integer.MAX_VALUE + " time units");
        }
        Duration limit = Duration.ofNanos(options.timeout() * options.timeUnitMicros() * 1000).plus(GRACE);
        try (ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            TronArguments arguments = new TronArguments(model, "127.0.0.1", server.getLocalPort(),
                    delayArgument(options), options.timeout(), options.seed(), null, List.of());
            try (RunningTron tron = launcher.start(arguments, echo, limit)) {
                Socket socket = awaitTron(server, tron);
                Bridge bridge = new Bridge(testInterface, sut, options);
                try (TronAdapterClient client = TronAdapterClient.over(socket, TronAdapterClient.TimeMode.REAL_TIME)) {
                    bridge.run(client);
                    int exit = tron.waitFor(limit);
                    String printed = tron.output();
                    return bridge.result(TronOutput.parse(printed), exit, printed);
                } finally {
                    sut.stop();
                }
            }
        }
    }

    private static Socket awaitTron(ServerSocket server, RunningTron tron) throws IOException, InterruptedException {
        server.setSoTimeout(200);
        long deadline = System.nanoTime() + CONNECT_TIMEOUT.toNanos();
        while (true) {
            try {
                return server.accept();
            } catch (SocketTimeoutException e) {
                if (!tron.isRunning()) {
                    int exit = tron.waitFor(Duration.ofSeconds(1));
                    throw new IOException("TRON ended (exit code " + exit + ") without connecting to DTRON; it"
                            + " printed: " + tail(tron.output()));
                }
                if (System.nanoTime() > deadline) {
                    throw new IOException("TRON did not connect to DTRON within " + CONNECT_TIMEOUT.toSeconds()
                            + " s; it printed: " + tail(tron.output()));
                }
            }
        }
    }

    private static String tail(String output) {
        String text = output.strip();
        if (text.isEmpty()) {
            return "(nothing)";
        }
        return text.length() > 600 ? "..." + text.substring(text.length() - 600) : text;
    }

    /** Carries inputs from TRON to the system under test and outputs back, and counts them. */
    private static final class Bridge {
        private final TestInterface testInterface;
        private final Adapter sut;
        private final TestOptions options;
        private final Map<Integer, TestInterface.ObservableChannel> inputs = new HashMap<>();
        private final Map<String, Integer> outputIds = new HashMap<>();
        private final AtomicInteger inputCount = new AtomicInteger();
        private final AtomicInteger outputCount = new AtomicInteger();
        private final CountDownLatch sutStarted = new CountDownLatch(1);
        private volatile String lost;
        private long startNanos;
        private long endNanos;

        Bridge(TestInterface testInterface, Adapter sut, TestOptions options) {
            this.testInterface = testInterface;
            this.sut = sut;
            this.options = options;
        }

        void run(TronAdapterClient client) throws IOException, InterruptedException {
            for (TestInterface.ObservableChannel c : testInterface.inputs()) {
                int id = client.registerInput(c.modelName());
                for (TestInterface.AttachedVariable v : c.variables()) {
                    client.addInputVariable(id, v.variable().name());
                }
                inputs.put(id, c);
            }
            for (TestInterface.ObservableChannel c : testInterface.outputs()) {
                int id = client.registerOutput(c.modelName());
                for (TestInterface.AttachedVariable v : c.variables()) {
                    client.addOutputVariable(id, v.variable().name());
                }
                outputIds.put(c.name(), id);
            }
            client.setTimeUnit(options.timeUnitMicros());
            client.setTimeout((int) options.timeout());
            startNanos = System.nanoTime();
            client.start((channel, values) -> input(channel, values));
            sut.start(context(client));
            sutStarted.countDown();
            client.awaitEnd(Duration.ofNanos(Long.MAX_VALUE));
            endNanos = System.nanoTime();
        }

        private void input(int channel, int[] values) {
            try {
                sutStarted.await();
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return;
            }
            TestInterface.ObservableChannel c = inputs.get(channel);
            Map<String, Integer> named = new LinkedHashMap<>();
            for (int i = 0; i < values.length; i++) {
                named.put(c.variables().get(i).name(), values[i]);
            }
            inputCount.incrementAndGet();
            sut.perform(new Event(c.name(), named));
        }

        private AdapterContext context(TronAdapterClient client) {
            return new AdapterContext() {
                @Override
                public void report(Event output) {
                    Integer id = outputIds.get(output.channel());
                    if (id == null) {
                        LOG.warn("the system under test reported '{}', which is not an output of the interface",
                                output.channel());
                        return;
                    }
                    int[] values = Wire.values(testInterface.output(output.channel()).orElseThrow().variables(),
                            output);
                    if (client.reportOutput(id, values)) {
                        outputCount.incrementAndGet();
                    }
                }

                /** TRON's protocol carries no event times: TRON stamps an output when it arrives. */
                @Override
                public void report(Event output, long eventMicros) {
                    report(output);
                }

                /** TRON's protocol carries no acknowledgements: TRON takes an input as applied when it sent it. */
                @Override
                public void inputApplied(long ordinal, long eventMicros) {
                }

                @Override
                public void inconclusive(String reason) {
                    lost = reason;
                    client.close();
                }

                @Override
                public TestClock clock() {
                    return new TestClock() {
                        @Override
                        public long nowMicros() {
                            return client.nowMicros();
                        }

                        @Override
                        public Scheduled schedule(long delayMicros, Runnable task) {
                            return client.schedule(delayMicros, task)::cancel;
                        }
                    };
                }

                @Override
                public TestInterface testInterface() {
                    return testInterface;
                }

                @Override
                public long timeUnitMicros() {
                    return options.timeUnitMicros();
                }
            };
        }

        TestResult result(TronOutput output, int exit, String text) throws IOException {
            Verdict verdict = output.verdict().map(Verdict::valueOf).orElse(null);
            if (verdict == null) {
                for (Verdict v : Verdict.values()) {
                    if (v.exitCode() == exit) {
                        verdict = v;
                    }
                }
            }
            if (verdict == null) {
                throw new IOException("TRON exited with code " + exit + " and printed no verdict: " + tail(text));
            }
            String explanation = output.explanation().orElse("TRON's verdict (exit code " + exit + ")");
            if (lost != null) {
                explanation += "; the system under test was lost: " + lost;
            }
            return new TestResult(verdict, explanation, output.seed().orElse(options.seed()), inputCount.get(),
                    outputCount.get(), (endNanos - startNanos) / 1000);
        }
    }
}
