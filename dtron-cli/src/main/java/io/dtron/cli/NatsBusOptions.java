package io.dtron.cli;

import io.dtron.api.DtronOptions;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.function.Function;
import java.util.function.Supplier;
import java.util.regex.Pattern;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;

/**
 * The options of a NATS bus ({@code --bus} and its {@code --nats-*} options), mixed into {@code dtron run}: their
 * checks, and the member options they make.
 */
final class NatsBusOptions {
    private static final Pattern BUS_NAME = Pattern.compile("[A-Za-z0-9_-]{1,64}");

    @Option(names = "--bus", paramLabel = "nats://HOST:PORT[,...]",
            description = "Use the NATS JetStream bus on these servers (comma-separated, servers of one NATS"
                    + " cluster) instead of the embedded JGroups bus; members in Java, Python and C (adapters,"
                    + " plants, taps) join it. The cluster name names the bus's stream.")
    private String bus;

    @Option(names = "--nats-user", paramLabel = "USER",
            description = "With --bus: authenticate as USER, with the password in --nats-password-file.")
    private String user;

    @Option(names = "--nats-password-file", paramLabel = "FILE",
            description = "With --bus and --nats-user: the file holding the password.")
    private Path passwordFile;

    @Option(names = "--nats-token-file", paramLabel = "FILE",
            description = "With --bus: authenticate with the token held in FILE.")
    private Path tokenFile;

    @Option(names = "--nats-creds", paramLabel = "FILE",
            description = "With --bus: authenticate with a NATS credentials file (user JWT and nkey seed).")
    private Path creds;

    @Option(names = "--nats-nkey", paramLabel = "FILE",
            description = "With --bus: authenticate with the nkey seed held in FILE.")
    private Path nkey;

    @Option(names = "--nats-tls-ca", paramLabel = "FILE",
            description = "With --bus: talk TLS to the servers, trusting the certificate authorities in this PEM file.")
    private Path tlsCa;

    @Option(names = "--nats-replicas", paramLabel = "N",
            description = "With --bus: the replicas of the bus's stream when this command creates it (the stream"
                    + " does not exist yet; default 1; 3 in a cluster of three servers survives one failing).")
    private Integer replicas;

    /** Whether {@code --bus} was given: the bus is NATS, not the embedded JGroups one. */
    boolean given() {
        return bus != null;
    }

    /**
     * Checks the options: the {@code --nats-*} ones only with {@code --bus}, in pairs where they go in pairs, with
     * values in range, and the bus's name ({@code cluster}) as a NATS stream name.
     */
    void check(String cluster, Function<String, ParameterException> usage) {
        boolean natsOptions = user != null || passwordFile != null || tokenFile != null || creds != null
                || nkey != null || tlsCa != null || replicas != null;
        if (bus == null) {
            if (natsOptions) {
                throw usage.apply("--nats-user, --nats-password-file, --nats-token-file, --nats-creds, --nats-nkey,"
                        + " --nats-tls-ca and --nats-replicas are for a NATS bus: give its servers with --bus"
                        + " nats://HOST:PORT");
            }
            return;
        }
        if ((user == null) != (passwordFile == null)) {
            throw usage.apply("--nats-user and --nats-password-file go together");
        }
        if (!BUS_NAME.matcher(cluster).matches()) {
            throw usage.apply("--cluster: a NATS bus name is 1 to 64 letters, digits, '_' or '-': '" + cluster + "'");
        }
        if (replicas != null && (replicas < 1 || replicas > 5)) {
            throw usage.apply("--nats-replicas must be in 1..5: " + replicas);
        }
        servers(usage);
    }

    /** The servers of {@code --bus}. */
    List<String> servers(Function<String, ParameterException> usage) {
        List<String> servers = List.of(bus.split(",", -1)).stream().map(String::trim).toList();
        for (String server : servers) {
            if (!server.matches("(nats|tls)://[^\\s/]+")) {
                throw usage.apply("--bus takes NATS server URLs, nats://HOST:PORT or tls://HOST:PORT, separated by"
                        + " commas: '" + server + "'");
            }
        }
        return servers;
    }

    /** Makes the options of a member on bus {@code cluster}; reads the secret files once, now. */
    Supplier<DtronOptions.Builder> memberOptions(String cluster, Function<String, ParameterException> usage) {
        List<String> servers = servers(usage);
        String password = passwordFile == null ? null : secret(passwordFile, "--nats-password-file", usage);
        String token = tokenFile == null ? null : secret(tokenFile, "--nats-token-file", usage);
        for (Path file : new Path[] {creds, nkey, tlsCa}) {
            if (file != null && !Files.isReadable(file)) {
                throw usage.apply("cannot read " + file);
            }
        }
        return () -> {
            DtronOptions.Builder builder = DtronOptions.builder().clusterName(cluster).natsServers(servers);
            if (user != null) {
                builder.natsUser(user, password);
            }
            if (token != null) {
                builder.natsToken(token);
            }
            if (creds != null) {
                builder.natsCredentialsFile(creds);
            }
            if (nkey != null) {
                builder.natsNkeyFile(nkey);
            }
            if (tlsCa != null) {
                builder.natsTlsCaFile(tlsCa);
            }
            if (replicas != null) {
                builder.natsReplicas(replicas);
            }
            return builder;
        };
    }

    /** The first line of a file holding a password or token. */
    private static String secret(Path file, String option, Function<String, ParameterException> usage) {
        try {
            String value = Files.readString(file).lines().findFirst().orElse("").trim();
            if (value.isEmpty()) {
                throw usage.apply(option + ": " + file + " is empty");
            }
            return value;
        } catch (IOException e) {
            throw usage.apply(option + ": cannot read " + file);
        }
    }
}
