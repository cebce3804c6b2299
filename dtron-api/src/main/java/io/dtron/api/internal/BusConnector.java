package io.dtron.api.internal;

import io.dtron.api.DtronOptions;
import io.dtron.bus.internal.Transport;
import io.dtron.bus.internal.BusKeys;
import io.dtron.bus.internal.JGroupsSettings;
import io.dtron.bus.internal.JGroupsTransport;
import io.dtron.bus.internal.NatsSettings;
import io.dtron.bus.internal.NatsTransport;
import java.util.HexFormat;
import java.util.Optional;
import java.util.concurrent.ThreadLocalRandom;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/** Not API. Opens the transport that {@link DtronOptions} describe, with the bus's secret ({@link BusKeys}). */
public final class BusConnector {
    private static final Logger LOG = LoggerFactory.getLogger(BusConnector.class);

    private BusConnector() {
    }

    /** Returns a fresh member id: {@code dtron-<pid>-<8 hex digits>}. */
    public static String generateMemberName() {
        byte[] random = new byte[4];
        ThreadLocalRandom.current().nextBytes(random);
        return "dtron-" + ProcessHandle.current().pid() + "-" + HexFormat.of().formatHex(random);
    }

    /**
     * Returns the bus's secret for the options: none when insecure, or in-JVM without a secret given (members of one
     * JVM exchange messages in memory); else the one given, or the key file's.
     *
     * @throws BusKeys.KeyFileException if the key file cannot be read, created or used
     */
    public static Optional<String> secret(DtronOptions options) {
        if (options.isInsecure() || options.isInJvm() && options.getSecret().isEmpty()) {
            return Optional.empty();
        }
        return Optional.of(BusKeys.secret(options.getSecret(), options.getKeyFile()));
    }

    /**
     * Returns the JGroups settings for the options, with the given member name.
     *
     * @throws BusKeys.KeyFileException if the key file cannot be read, created or used
     */
    public static JGroupsSettings settings(DtronOptions options, String memberName) {
        return new JGroupsSettings(options.getClusterName(), memberName, options.getBindAddress(),
                options.getPort(), options.getPortRange(), options.getInitialMembers(), secret(options),
                options.isEncrypt(), options.isInJvm());
    }

    /**
     * Returns the NATS settings for the options, with the given member name.
     *
     * @throws BusKeys.KeyFileException if the key file cannot be read, created or used
     */
    public static NatsSettings natsSettings(DtronOptions options, String memberName) {
        return new NatsSettings(options.getClusterName(), memberName, options.getNatsServers(), options.getNatsUser(),
                options.getNatsPassword(), options.getNatsToken(), options.getNatsCredentialsFile(),
                options.getNatsNkeyFile(), options.getNatsTlsCaFile(), options.getNatsReplicas(),
                secret(options).map(BusKeys::macKey));
    }

    /**
     * Joins the bus: NATS when the options name NATS servers, else JGroups.
     *
     * @throws Exception what the transport throws when it cannot join
     */
    public static Transport connect(DtronOptions options) throws Exception {
        String memberName = options.getMemberName().orElseGet(BusConnector::generateMemberName);
        if (options.isInsecure()) {
            LOG.warn("INSECURE: member {} joins bus '{}' without the bus's secret: any process that can reach the bus"
                    + " may speak on it as this member's peers do, and members with the secret do not hear this one",
                    memberName, options.getClusterName());
        }
        if (!options.getNatsServers().isEmpty()) {
            return NatsTransport.connect(natsSettings(options, memberName));
        }
        return JGroupsTransport.connect(settings(options, memberName));
    }
}
