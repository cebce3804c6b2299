package io.dtron.bus.internal;

import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.Optional;

/**
 * Not API. What a {@link JGroupsTransport} needs to know to join its cluster.
 *
 * @param clusterName    the JGroups cluster; members of different clusters never see each other
 * @param memberName     this member's logical name, unique in the cluster
 * @param bindAddress    the interface every socket of the member listens on (the bus and failure detection)
 * @param port           the first port of the member's ports
 * @param portRange      how many ports above {@code port} the member may use: the lower half for the bus (and
 *                       probed at each initial member), the upper half for failure detection; at least 1 over TCP
 * @param initialMembers where to look for other members; empty means {@code bindAddress:port} and the bus ports
 *                       above it
 * @param secret         shared secret for authentication (and the encryption key), if any
 * @param encrypt        whether to encrypt all messages between members (needs a secret)
 * @param inJvm          whether to use the in-JVM transport without sockets instead of TCP
 */
public record JGroupsSettings(
        String clusterName,
        String memberName,
        InetAddress bindAddress,
        int port,
        int portRange,
        List<InetSocketAddress> initialMembers,
        Optional<String> secret,
        boolean encrypt,
        boolean inJvm) {

    /** Checks the settings and makes them immutable. */
    public JGroupsSettings {
        Objects.requireNonNull(clusterName, "clusterName");
        Objects.requireNonNull(memberName, "memberName");
        Objects.requireNonNull(bindAddress, "bindAddress");
        initialMembers = List.copyOf(initialMembers);
        Objects.requireNonNull(secret, "secret");
        if (port < 1 || port > 65535) {
            throw new IllegalArgumentException("port must be in 1..65535: " + port);
        }
        if (portRange < 0 || port + portRange > 65535) {
            throw new IllegalArgumentException("port range must be >= 0 and end at 65535 at most: " + portRange);
        }
        if (encrypt && secret.isEmpty()) {
            throw new IllegalArgumentException("encryption needs a shared secret");
        }
        if (!inJvm && portRange < 1) {
            throw new IllegalArgumentException(NO_ROOM_FOR_FAILURE_DETECTION);
        }
    }

    /** Why a port range of 0 does not do over TCP. */
    static final String NO_ROOM_FOR_FAILURE_DETECTION = "a port range of 0 leaves no port for failure detection:"
            + " each member listens on two ports (give a port range of 1 or more)";

    /**
     * Returns how many bus ports there are, {@code port .. port+busPorts()-1}: how many members one address holds.
     * A member listening for the bus on port P listens for failure detection on {@code P + busPorts()}, so that
     * every port a member uses lies in {@code port .. port+portRange}.
     */
    public int busPorts() {
        return (portRange + 1) / 2;
    }

    /**
     * Returns the addresses TCPPING probes: each initial member (by default the
     * bind address and port) at its port and the bus ports above it ({@link #busPorts()} in all).
     */
    List<InetSocketAddress> discoveryAddresses() {
        List<InetSocketAddress> starts = initialMembers.isEmpty()
                ? List.of(new InetSocketAddress(bindAddress, port))
                : initialMembers;
        List<InetSocketAddress> probed = new ArrayList<>();
        for (InetSocketAddress start : starts) {
            for (int p = start.getPort(); p < Math.min(start.getPort() + busPorts(), 65536); p++) {
                probed.add(new InetSocketAddress(start.getAddress(), p));
            }
        }
        return List.copyOf(probed);
    }

    @Override
    public String toString() {
        return "JGroupsSettings[cluster=" + clusterName + ", member=" + memberName
                + (inJvm ? ", in-JVM" : ", bind=" + bindAddress.getHostAddress() + ":" + port + "+" + portRange
                        + (initialMembers.isEmpty() ? "" : ", initialMembers=" + initialMembers))
                + ", auth=" + secret.isPresent() + ", encrypt=" + encrypt + "]";
    }
}
