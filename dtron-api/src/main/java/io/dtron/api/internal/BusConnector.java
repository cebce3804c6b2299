package io.dtron.api.internal;

import io.dtron.api.DtronOptions;
import io.dtron.bus.Transport;
import io.dtron.bus.internal.JGroupsSettings;
import io.dtron.bus.internal.JGroupsTransport;
import io.dtron.bus.internal.MessageCodes;
import io.dtron.bus.internal.NatsSettings;
import io.dtron.bus.internal.NatsTransport;
import java.nio.charset.StandardCharsets;
import java.util.HexFormat;
import java.util.concurrent.ThreadLocalRandom;

/** Not API. Opens the transport that {@link DtronOptions} describe. */
public final class BusConnector {
    private BusConnector() {
    }

    /** Returns a fresh member id: {@code dtron-<pid>-<8 hex digits>}. */
    public static String generateMemberName() {
        byte[] random = new byte[4];
        ThreadLocalRandom.current().nextBytes(random);
        return "dtron-" + ProcessHandle.current().pid() + "-" + HexFormat.of().formatHex(random);
    }

    /** Returns the JGroups settings for the options, with the given member name. */
    public static JGroupsSettings settings(DtronOptions options, String memberName) {
        return new JGroupsSettings(options.getClusterName(), memberName, options.getBindAddress(),
                options.getPort(), options.getPortRange(), options.getInitialMembers(), options.getSecret(),
                options.isEncrypt(), options.isInJvm());
    }

    /** Returns the NATS settings for the options, with the given member name. */
    public static NatsSettings natsSettings(DtronOptions options, String memberName) {
        return new NatsSettings(options.getClusterName(), memberName, options.getNatsServers(), options.getNatsUser(),
                options.getNatsPassword(), options.getNatsToken(), options.getNatsCredentialsFile(),
                options.getNatsNkeyFile(), options.getNatsTlsCaFile(), options.getNatsReplicas(),
                options.getSecret().map(secret -> MessageCodes.key(secret.getBytes(StandardCharsets.UTF_8))));
    }

    /**
     * Joins the bus: NATS when the options name NATS servers, else JGroups.
     *
     * @throws Exception what the transport throws when it cannot join
     */
    public static Transport connect(DtronOptions options) throws Exception {
        String memberName = options.getMemberName().orElseGet(BusConnector::generateMemberName);
        if (!options.getNatsServers().isEmpty()) {
            return NatsTransport.connect(natsSettings(options, memberName));
        }
        return JGroupsTransport.connect(settings(options, memberName));
    }
}
