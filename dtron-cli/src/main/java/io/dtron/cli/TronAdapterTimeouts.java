package io.dtron.cli;

import io.dtron.tron.TronSocketAdapter;
import java.time.Duration;
import picocli.CommandLine.Option;

/**
 * How long an adapter written for Uppaal TRON may take ({@code --config-timeout}, {@code --reply-timeout}), mixed
 * into {@code dtron tron} and {@code dtron run --tron-adapter}.
 */
final class TronAdapterTimeouts {
    private static final long DEFAULT_SECONDS = 10;

    @Option(names = "--config-timeout", paramLabel = "SECONDS",
            description = "How long a TRON adapter may stay silent while it configures the test (default 10).")
    private Long configTimeout;

    @Option(names = "--reply-timeout", paramLabel = "SECONDS",
            description = "In virtual time: how long a TRON adapter may take to acknowledge an input (default 10).")
    private Long replyTimeout;

    /** Whether either option was given. */
    boolean given() {
        return configTimeout != null || replyTimeout != null;
    }

    /** What is wrong with the values given, or null. */
    String problem() {
        if (replyTimeout != null && (replyTimeout <= 0 || replyTimeout > RunDefaults.MAX_WAIT_SECONDS)) {
            return "--reply-timeout must be a positive number of seconds, at most " + RunDefaults.MAX_WAIT_SECONDS
                    + " (about 292 years)";
        }
        if (configTimeout != null && (configTimeout <= 0 || configTimeout > Integer.MAX_VALUE / 1000)) {
            return "--config-timeout must be a positive number of seconds, at most " + Integer.MAX_VALUE / 1000;
        }
        return null;
    }

    /** {@code settings} with these timeouts. */
    TronSocketAdapter.Settings applyTo(TronSocketAdapter.Settings settings) {
        return settings.withReplyTimeout(Duration.ofSeconds(replyTimeout == null ? DEFAULT_SECONDS : replyTimeout))
                .withConfigurationTimeout(Duration.ofSeconds(configTimeout == null ? DEFAULT_SECONDS : configTimeout));
    }
}
