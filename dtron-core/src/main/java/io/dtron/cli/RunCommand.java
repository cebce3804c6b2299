package io.dtron.cli;

import io.dtron.engine.Adapter;
import io.dtron.engine.DelayPolicy;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.xta.Diagnostic;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.Writer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Callable;
import java.util.concurrent.atomic.AtomicInteger;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron run MODEL --sut CLASS}: tests an in-process system under test against a model with the
 * embedded engine and prints the verdict with its explanation. Exit codes: 0 passed, 2 failed, 3
 * inconclusive, 1 usage or model error.
 */
@Command(name = "run", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Test a system under test online against a model, with DTRON's engine.",
                "The model's environment chooses inputs and their timing; the system's outputs and their times are"
                        + " checked against the model. Prints the seed, progress on long runs, and the verdict with"
                        + " its explanation.",
                "Exit code 0 PASSED, 2 FAILED, 3 INCONCLUSIVE, 1 usage or model error."})
final class RunCommand implements Callable<Integer> {
    private static final long PROGRESS_EVERY_NANOS = 5_000_000_000L;

    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "MODEL", description = "The model (.xml, .xta).")
    private Path model;

    @Option(names = "--sut", required = true, paramLabel = "CLASS[:VARIANT]",
            description = "The system under test: a class implementing io.dtron.engine.Adapter, optionally with a"
                    + " variant name passed to its constructor (e.g. io.dtron.models.lamp.SmartLamp:late).")
    private String sut;

    @Option(names = "--classpath", split = ",", paramLabel = "PATH",
            description = "Jars or folders to load the system under test from (comma-separated).")
    private List<Path> classpath = List.of();

    @Option(names = "--interface", paramLabel = "FILE.trn",
            description = "TRON interface file; by default i_/o_ channel names give the interface.")
    private Path interfaceFile;

    @Option(names = "--virtual-time", description = "Run in virtual time: deterministic and as fast as the CPU allows.")
    private boolean virtualTime;

    @Option(names = "--seed", paramLabel = "N", description = "Seed of the random choices (default: from the clock).")
    private Long seed;

    @Option(names = "--timeout", paramLabel = "N",
            description = "Test duration in model time units (default: the interface file's, else 1000).")
    private Long timeout;

    @Option(names = "--timeunit", paramLabel = "US",
            description = "Microseconds per model time unit (default: the interface file's precision, else 1000).")
    private Long timeUnit;

    @Option(names = "--delay-policy", paramLabel = "POLICY", defaultValue = "random",
            description = "How input times are chosen: random, eager, lazy or random-bounded (default: random).")
    private String delayPolicy;

    @Option(names = "--delay-bound", paramLabel = "N", defaultValue = "0",
            description = "For random-bounded: the largest delay after an input's window opens, in time units.")
    private long delayBound;

    @Option(names = "--trace", paramLabel = "FILE", description = "Write every event as one JSON line to FILE.")
    private Path trace;

    @Override
    public Integer call() {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        Network network;
        TestInterface testInterface;
        try {
            network = ModelLoader.load(model);
            testInterface = interfaceFile == null ? TestInterface.fromNames(network)
                    : TestInterface.fromFile(network, interfaceFile);
        } catch (ModelException e) {
            err.println(model + ": " + e.errors().size() + " error" + (e.errors().size() == 1 ? "" : "s"));
            for (Diagnostic d : e.diagnostics()) {
                err.println("  " + d.format());
            }
            return 1;
        }
        if (testInterface.inputs().isEmpty() && testInterface.outputs().isEmpty()) {
            err.println("dtron run: " + model + " has no inputs or outputs: name channels i_x / o_y, or give"
                    + " --interface FILE.trn");
            return 1;
        }
        DelayPolicy policy;
        try {
            policy = DelayPolicy.valueOf(delayPolicy.toUpperCase(Locale.ROOT).replace('-', '_'));
        } catch (IllegalArgumentException e) {
            err.println("dtron run: unknown delay policy '" + delayPolicy
                    + "' (use random, eager, lazy or random-bounded)");
            return 1;
        }
        long unit = timeUnit != null ? timeUnit : testInterface.timeUnitMicros() != null
                ? testInterface.timeUnitMicros() : 1000;
        long units = timeout != null ? timeout : testInterface.timeout() != null ? testInterface.timeout() : 1000;
        long runSeed = seed != null ? seed : System.nanoTime() & 0xffffffffL;
        TestOptions options;
        Adapter adapter;
        try {
            options = new TestOptions(runSeed, unit, units, policy, delayBound, virtualTime);
            adapter = SystemUnderTest.create(sut, classpath);
        } catch (IllegalArgumentException e) {
            err.println("dtron run: " + e.getMessage());
            return 1;
        }
        out.println("dtron run: " + model + " against " + sut + ", seed " + runSeed + ", " + units + " time units of "
                + unit + " us" + (virtualTime ? " in virtual time" : ""));
        out.flush();
        try (Writer traceWriter = trace == null ? null : Files.newBufferedWriter(trace, StandardCharsets.UTF_8)) {
            OnlineTester tester = new OnlineTester(network, testInterface, adapter, options);
            if (traceWriter != null) {
                JsonTrace json = new JsonTrace(traceWriter, unit);
                json.start(runSeed, model.toString(), units, virtualTime);
                tester.addListener(json);
            }
            tester.addListener(new Progress(out));
            TestResult result = tester.run();
            out.println(result.verdict() + ": " + result.explanation());
            out.println("statistics: " + result.statisticsLine() + " (seed verdict inputs outputs duration-us)");
            out.flush();
            return result.verdict().exitCode();
        } catch (UnsupportedModelException e) {
            err.println("dtron run: " + model + ": " + e.getMessage());
            return 1;
        } catch (IOException e) {
            err.println("dtron run: cannot write the trace " + trace + ": " + e.getMessage());
            return 1;
        }
    }

    /** A progress line every few seconds of wall-clock time: elapsed test time, inputs, outputs. */
    private static final class Progress implements TestListener {
        private final PrintWriter out;
        private final long start = System.nanoTime();
        private long lastLine = System.nanoTime();
        private final AtomicInteger inputs = new AtomicInteger();
        private final AtomicInteger outputs = new AtomicInteger();

        Progress(PrintWriter out) {
            this.out = out;
        }

        @Override
        public void inputApplied(Event input, long micros) {
            inputs.incrementAndGet();
            maybePrint(micros);
        }

        @Override
        public void outputObserved(Event output, long micros) {
            outputs.incrementAndGet();
            maybePrint(micros);
        }

        private void maybePrint(long micros) {
            long now = System.nanoTime();
            if (now - lastLine >= PROGRESS_EVERY_NANOS) {
                lastLine = now;
                out.printf("progress: %.1f s elapsed, test time %.3f s, %d inputs, %d outputs%n",
                        (now - start) / 1e9, micros / 1e6, inputs.get(), outputs.get());
                out.flush();
            }
        }
    }
}
