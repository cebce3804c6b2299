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
 * @param bindAddress    the interface the member listens on
 * @param port           the first of the bus ports
 * @param portRange      how many ports above {@code port} are bus ports too: the member listens on one of them, and
 *                       looks for the others on all of them at each initial member
 * @param initialMembers where to look for other members; empty means {@code bindAddress:port} and the bus ports
 *                       above it
 * @param secret         the bus's secret ({@link BusKeys}): the key of the codes every frame carries over TCP
 *                       ({@link GuardedTcp}) and of the encryption; empty for an insecure member, whose codes are
 *                       made with a public key, so that it talks only to insecure members
 * @param encrypt        whether to encrypt all messages between members (needs the secret)
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
    }

    /**
     * Returns how many bus ports there are, {@code port .. port+portRange}: how many members one address holds. A
     * member listens on one of them only.
     */
    public int busPorts() {
        return portRange + 1;
    }

    /** Returns the key of the codes of this member's frames: the bus's, or the public one of insecure members. */
    byte[] macKey() {
        return BusKeys.macKey(secret.orElse(BusKeys.INSECURE_SECRET));
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
                + (inJvm ? "" : secret.isPresent() ? ", secure" : ", INSECURE") + ", encrypt=" + encrypt + "]";
    }
}
