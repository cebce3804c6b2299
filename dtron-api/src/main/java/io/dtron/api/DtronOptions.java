package io.dtron.api;

import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.Collection;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Optional;

/**
 * How a {@link Dtron} joins the bus. Immutable; made with {@link #builder()}.
 *
 * <p>The defaults need no configuration on one host: the bus binds to the
 * loopback interface and members find each other by probing the ports
 * {@code port .. port+portRange} there. For a LAN, give the
 * {@linkplain Builder#bindAddress interface} to bind to and the
 * {@linkplain Builder#initialMembers hosts} where to look for members (each
 * probed over the same port range). A {@linkplain Builder#secret shared
 * secret} makes members prove it before joining;
 * {@linkplain Builder#encrypt encryption} encrypts all traffic with a key
 * derived from it. {@linkplain Builder#inJvm In-JVM mode} joins only members
 * of the same JVM, without sockets.
 */
public final class DtronOptions {
    /** The cluster name used when none is given. */
    public static final String DEFAULT_CLUSTER = "dtron";
    /** The first port probed and bound to when none is given. */
    public static final int DEFAULT_PORT = 7800;
    /** How many ports above the first are probed and bound to when not told otherwise. */
    public static final int DEFAULT_PORT_RANGE = 30;

    private final String clusterName;
    private final Optional<String> memberName;
    private final InetAddress bindAddress;
    private final int port;
    private final int portRange;
    private final List<InetSocketAddress> initialMembers;
    private final Optional<String> secret;
    private final boolean encrypt;
    private final boolean inJvm;
    private final Optional<Map<String, IDtronChannel>> channels;
    private final boolean tester;
    private final Duration clockShift;

    private DtronOptions(Builder b) {
        clusterName = b.clusterName;
        memberName = b.memberName;
        bindAddress = b.bindAddress;
        port = b.port;
        portRange = b.portRange;
        initialMembers = b.initialMembers;
        secret = b.secret;
        encrypt = b.encrypt;
        inJvm = b.inJvm;
        channels = b.channels;
        tester = b.tester;
        clockShift = b.clockShift;
    }

    /** Returns a builder with the defaults. */
    public static Builder builder() {
        return new Builder();
    }

    /** Returns the cluster name; only members of the same cluster see each other. */
    public String getClusterName() {
        return clusterName;
    }

    /** Returns this member's id on the bus, if given; otherwise one is generated on connecting. */
    public Optional<String> getMemberName() {
        return memberName;
    }

    /** Returns the interface to bind to. */
    public InetAddress getBindAddress() {
        return bindAddress;
    }

    /** Returns the first port to bind to and to probe. */
    public int getPort() {
        return port;
    }

    /** Returns how many ports above {@link #getPort()} to bind to and to probe. */
    public int getPortRange() {
        return portRange;
    }

    /** Returns where to look for members; empty means at the bind address. Immutable. */
    public List<InetSocketAddress> getInitialMembers() {
        return initialMembers;
    }

    /** Returns the shared secret that members must prove to join, if any. */
    public Optional<String> getSecret() {
        return secret;
    }

    /** Returns whether traffic between members is encrypted. */
    public boolean isEncrypt() {
        return encrypt;
    }

    /** Returns whether only members in this JVM are joined, without sockets. */
    public boolean isInJvm() {
        return inJvm;
    }

    /**
     * Returns the declared channels by name, if declared: then a message on any
     * other channel is rejected as unknown. Immutable.
     */
    public Optional<Map<String, IDtronChannel>> getChannels() {
        return channels;
    }

    /** Returns whether this member is the tester, which announces itself and answers clock-offset pings. */
    public boolean isTester() {
        return tester;
    }

    /** Returns the shift added to this member's wall clock, for tests only; zero normally. */
    public Duration getClockShiftForTesting() {
        return clockShift;
    }

    @Override
    public String toString() {
        return "DtronOptions[cluster=" + clusterName + memberName.map(n -> ", member=" + n).orElse("")
                + (inJvm ? ", in-JVM" : ", bind=" + bindAddress.getHostAddress() + ", port=" + port + "+" + portRange
                        + (initialMembers.isEmpty() ? "" : ", initialMembers=" + initialMembers))
                + ", auth=" + secret.isPresent() + ", encrypt=" + encrypt
                + channels.map(c -> ", channels=" + c.keySet()).orElse("") + (tester ? ", tester" : "")
                + (clockShift.isZero() ? "" : ", clockShift=" + clockShift) + "]";
    }

    /** Builds {@link DtronOptions}. Not thread-safe. */
    public static final class Builder {
        private String clusterName = DEFAULT_CLUSTER;
        private Optional<String> memberName = Optional.empty();
        private InetAddress bindAddress = InetAddress.getLoopbackAddress();
        private int port = DEFAULT_PORT;
        private int portRange = DEFAULT_PORT_RANGE;
        private List<InetSocketAddress> initialMembers = List.of();
        private Optional<String> secret = Optional.empty();
        private boolean encrypt;
        private boolean inJvm;
        private Optional<Map<String, IDtronChannel>> channels = Optional.empty();
        private boolean tester;
        private Duration clockShift = Duration.ZERO;

        private Builder() {
        }

        /** Sets the cluster name (default {@value DtronOptions#DEFAULT_CLUSTER}). */
        public Builder clusterName(String name) {
            if (Objects.requireNonNull(name, "name").isBlank()) {
                throw new IllegalArgumentException("cluster name is blank");
            }
            clusterName = name;
            return this;
        }

        /** Sets this member's id, which must be unique on the bus (default: generated). */
        public Builder memberName(String name) {
            if (Objects.requireNonNull(name, "name").isBlank()) {
                throw new IllegalArgumentException("member name is blank");
            }
            memberName = Optional.of(name);
            return this;
        }

        /** Sets the interface to bind to (default: loopback). */
        public Builder bindAddress(InetAddress address) {
            bindAddress = Objects.requireNonNull(address, "address");
            return this;
        }

        /** Sets the first port to bind to and to probe (default {@value DtronOptions#DEFAULT_PORT}). */
        public Builder port(int first) {
            if (first < 1 || first > 65535) {
                throw new IllegalArgumentException("port must be in 1..65535: " + first);
            }
            port = first;
            return this;
        }

        /** Sets how many ports above the first to bind to and to probe (default {@value DtronOptions#DEFAULT_PORT_RANGE}). */
        public Builder portRange(int range) {
            if (range < 0) {
                throw new IllegalArgumentException("port range is negative: " + range);
            }
            portRange = range;
            return this;
        }

        /** Sets the hosts and first ports where to look for members (default: the bind address and port). */
        public Builder initialMembers(Collection<InetSocketAddress> members) {
            initialMembers = List.copyOf(members);
            return this;
        }

        /** Requires every member to prove this shared secret before joining (default: none). */
        public Builder secret(String sharedSecret) {
            if (Objects.requireNonNull(sharedSecret, "sharedSecret").isEmpty()) {
                throw new IllegalArgumentException("secret is empty");
            }
            secret = Optional.of(sharedSecret);
            return this;
        }

        /** Encrypts all traffic between members with a key derived from the secret (default: off). */
        public Builder encrypt(boolean on) {
            encrypt = on;
            return this;
        }

        /** Joins only members in this JVM, without sockets (default: off). */
        public Builder inJvm(boolean on) {
            inJvm = on;
            return this;
        }

        /**
         * Declares every channel of the bus, as a tester knows them from its
         * model: a message on any other channel is then rejected as unknown,
         * and listeners and sent messages must use these templates.
         * Without this call, messages on channels without a listener are ignored.
         * DTRON's own channels ({@link Dtron#isReservedChannel}) are always known and
         * need not be declared; {@link Dtron#RUN_START} and {@link Dtron#RUN_STOP} may be.
         *
         * @throws IllegalArgumentException if two templates have the same name, or one has the name of a channel
         *                                  DTRON reserves and is not {@code RUN_START} or {@code RUN_STOP}
         */
        public Builder channels(Collection<? extends IDtronChannel> declared) {
            Map<String, IDtronChannel> byName = new LinkedHashMap<>();
            for (IDtronChannel channel : declared) {
                Dtron.checkNotReserved(channel);
                if (byName.put(channel.getChannelName(), channel) != null) {
                    throw new IllegalArgumentException("channel declared twice: " + channel.getChannelName());
                }
            }
            channels = Optional.of(Collections.unmodifiableMap(byName));
            return this;
        }

        /**
         * Makes this member the tester (default: off): it announces itself on the bus when it joins and when
         * members join, and answers the other members' pings, by which they estimate their clock's offset to its
         * clock. A member that publishes {@link Dtron#RUN_START} becomes the tester anyway, from then on.
         */
        public Builder tester(boolean on) {
            tester = on;
            return this;
        }

        /**
         * For tests only: adds {@code shift} to every time this member reads from its wall clock (publish, event,
         * receive and ping times, the run clock), as if its host's clock were off by that much (default: zero).
         */
        public Builder clockShiftForTesting(Duration shift) {
            clockShift = Objects.requireNonNull(shift, "shift");
            return this;
        }

        /**
         * Builds the options.
         *
         * @throws IllegalStateException if encryption is on without a secret, or the port range exceeds 65535
         */
        public DtronOptions build() {
            if (encrypt && secret.isEmpty()) {
                throw new IllegalStateException("encryption needs a secret");
            }
            if (port + portRange > 65535) {
                throw new IllegalStateException("ports " + port + ".." + (port + portRange) + " exceed 65535");
            }
            return new DtronOptions(this);
        }
    }
}
