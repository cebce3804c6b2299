package io.dtron.troninstaller;

import java.nio.file.Path;
import java.util.List;
import java.util.Objects;

/**
 * What DTRON passes to TRON when it launches it as its backend: TRON runs the model and connects, with its socket
 * adapter, to DTRON, which listens at {@code host:port} on the system under test's side.
 *
 * @param model       the model file
 * @param host        the address TRON connects to
 * @param port        the port TRON connects to
 * @param delayPolicy TRON's {@code -P} value ({@code random}, {@code eager}, {@code lazy} or {@code MIN,MAX}), or
 *                    null for TRON's default
 * @param future      TRON's {@code -F} value (how long to test, in model time units), or null
 * @param seed        TRON's {@code -X} value (the random seed), or null for TRON's own choice
 * @param verbosity   TRON's {@code -v} value, or null
 * @param extra       further options, passed as they are, before the model
 */
public record TronArguments(Path model, String host, int port, String delayPolicy, Long future, Long seed,
                            Integer verbosity, List<String> extra) {
    public TronArguments {
        Objects.requireNonNull(model, "model");
        Objects.requireNonNull(host, "host");
        if (port <= 0 || port > 65535) {
            throw new IllegalArgumentException("port " + port + " is not a TCP port (1 to 65535)");
        }
        extra = List.copyOf(extra);
    }

    /** The arguments after the executable, in TRON's order: options, the model, {@code --}, host and port. */
    public List<String> toList() {
        List<String> args = new java.util.ArrayList<>(List.of("-I", "SocketAdapter"));
        if (verbosity != null) {
            args.addAll(List.of("-v", verbosity.toString()));
        }
        if (delayPolicy != null) {
            args.addAll(List.of("-P", delayPolicy));
        }
        if (future != null) {
            args.addAll(List.of("-F", future.toString()));
        }
        if (seed != null) {
            args.addAll(List.of("-X", seed.toString()));
        }
        args.addAll(extra);
        args.add(model.toString());
        args.addAll(List.of("--", host, Integer.toString(port)));
        return args;
    }
}
