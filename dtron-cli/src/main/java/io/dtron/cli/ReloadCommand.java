package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannelValued;
import java.io.IOException;
import java.io.PrintWriter;
import java.net.InetAddress;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Map;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.Callable;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.ThreadLocalRandom;
import java.util.concurrent.TimeUnit;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code dtron reload VERSION}: hands a model version to the controller running on a bus ({@code dtron control
 * --reload-from-bus}) and prints what became of it, as the controller publishes it.
 */
@Command(name = "reload", mixinStandardHelpOptions = true, exitCodeOnInvalidInput = 1, exitCodeOnExecutionException = 1,
        description = {"Hand a new model version to the controller on the bus (dtron control --reload-from-bus): it"
                + " checks the version (it loads, its queries hold) and takes it at the next reset point, or refuses"
                + " it with the reason; this command prints what the controller said.",
                "Exit code 0 when the version was taken, 2 when it was refused, 3 when no controller said what became"
                        + " of it in time, 1 usage error."})
final class ReloadCommand implements Callable<Integer> {
    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "VERSION", description = "The new version of the model (.xml or .xta).")
    private Path version;

    @Option(names = "--queries", paramLabel = "FILE.q",
            description = "The queries the version must satisfy (default: the .q beside it, else those written in it,"
                    + " else those of the controller's model).")
    private Path queries;

    @Option(names = "--cluster", paramLabel = "NAME",
            description = "The controller's bus (default '" + DtronOptions.DEFAULT_CLUSTER + "'): the embedded JGroups"
                    + " bus on loopback, or the NATS bus of --bus.")
    private String cluster;

    @Mixin
    private NatsBusOptions nats;

    @Mixin
    private BusSecretOptions secret;

    @Option(names = "--wait-timeout", paramLabel = "SECONDS",
            description = "How long to wait for the controller to take or refuse the version (default 60).")
    private Long waitTimeout;

    @Override
    public Integer call() throws InterruptedException {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        try {
            return reload(out, err);
        } finally {
            out.flush();
            err.flush();
        }
    }

    private int reload(PrintWriter out, PrintWriter err) throws InterruptedException {
        String bus = cluster != null ? cluster : DtronOptions.DEFAULT_CLUSTER;
        if (bus.isBlank()) {
            throw usage("--cluster: the bus name is blank");
        }
        long seconds = waitTimeout == null ? 60 : waitTimeout;
        if (seconds <= 0 || seconds > RunDefaults.MAX_WAIT_SECONDS) {
            throw usage("--wait-timeout must be a positive number of seconds, at most " + RunDefaults.MAX_WAIT_SECONDS
                    + ": " + seconds);
        }
        nats.check(bus, this::usage);
        String text;
        try {
            Path own = queries != null ? queries : ModelVersionFile.beside(version);
            String q = queries != null || Files.isRegularFile(own) ? Files.readString(own, StandardCharsets.UTF_8)
                    : null;
            text = "{\"label\": " + JsonTrace.quote(version.getFileName().toString()) + ", \"model\": "
                    + JsonTrace.quote(Files.readString(version, StandardCharsets.UTF_8))
                    + (q == null ? "" : ", \"queries\": " + JsonTrace.quote(q)) + "}";
        } catch (IOException e) {
            err.println("dtron reload: cannot read " + e.getMessage());
            return 1;
        }
        if (text.getBytes(StandardCharsets.UTF_8).length > ModelVersionBus.MAX_TEXT_BYTES) {
            err.println("dtron reload: " + version + ": the version is larger than the "
                    + ModelVersionBus.MAX_TEXT_BYTES + " bytes a controller takes from the bus");
            return 1;
        }
        DtronOptions.Builder options = secret.apply(nats.given() ? nats.memberOptions(bus, this::usage).get()
                : DtronOptions.builder().clusterName(bus).bindAddress(InetAddress.getLoopbackAddress()));
        int number = ThreadLocalRandom.current().nextInt(1, Integer.MAX_VALUE);
        BlockingQueue<IDtronChannelValued> outcomes = new LinkedBlockingQueue<>();
        try (Dtron member = Dtron.connect(options.build())) {
            member.addDtronListener(new DtronListener(Dtron.MODEL_OUTCOME) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    if (message.getVariables().get("version") == number) {
                        outcomes.add(message);
                    }
                }
            });
            member.send(Dtron.MODEL_VERSION.constructValued(Map.of("version", number)), text);
            out.println("dtron reload: " + version + " sent on bus '" + bus + "' as version " + number);
            out.flush();
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(seconds);
            while (true) {
                IDtronChannelValued outcome = outcomes.poll(Math.max(0, deadline - System.nanoTime()),
                        TimeUnit.NANOSECONDS);
                if (outcome == null) {
                    err.println("dtron reload: within " + seconds + " s no controller on bus '" + bus + "' took or"
                            + " refused version " + number + " (is it running with --reload-from-bus?)");
                    return 3;
                }
                out.println(outcome.getText());
                out.flush();
                int code = outcome.getVariables().get("outcome");
                if (code != 1) {
                    return code == 0 ? 0 : 2;
                }
            }
        } catch (DtronException e) {
            err.println("dtron reload: " + e.getMessage() + (e.getCause() == null ? "" : ": "
                    + e.getCause().getMessage()));
            return 1;
        }
    }

    private ParameterException usage(String message) {
        return new ParameterException(spec.commandLine(), message);
    }
}
