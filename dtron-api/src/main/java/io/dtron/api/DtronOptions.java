package io.dtron.api;

import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.nio.file.Path;
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
 * <p>The defaults need no configuration on one host: every socket of the bus
 * listens on the loopback interface, and members find each other by probing
 * the bus ports there. A member uses two ports of {@code port .. port+portRange}:
 * a bus port P of the lower half, {@code port .. port+(portRange+1)/2-1} (the
 * ports probed), and {@code P + (portRange+1)/2} for failure detection; by
 * default 7800..7830 and 7831..7861, 31 members per address. When no bus port
 * is free with its failure detection port, {@link Dtron#connect(DtronOptions)}
 * throws a {@link DtronException} naming the ports in use. For a LAN, give the
 * {@linkplain Builder#bindAddress interface} to bind to and the
 * {@linkplain Builder#initialMembers hosts} where to look for members (each
 * probed over the same bus ports). A {@linkplain Builder#secret shared
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
    /**
     * How many ports above the first a member may use when not told otherwise: 61, so that the bus ports 7800..7830
     * (31 members per address) and their failure detection ports 7831..7861 fit.
     */
    public static final int DEFAULT_PORT_RANGE = 61;

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
    private final List<String> natsServers;
    private final Optional<String> natsUser;
    private final Optional<String> natsPassword;
    private final Optional<String> natsToken;
    private final Optional<Path> natsCredentialsFile;
    private final Optional<Path> natsNkeyFile;
    private final Optional<Path> natsTlsCaFile;
    private final int natsReplicas;

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
        natsServers = b.natsServers;
        natsUser = b.natsUser;
        natsPassword = b.natsPassword;
        natsToken = b.natsToken;
        natsCredentialsFile = b.natsCredentialsFile;
        natsNkeyFile = b.natsNkeyFile;
        natsTlsCaFile = b.natsTlsCaFile;
        natsReplicas = b.natsReplicas;
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

    /** Returns how many ports above {@link #getPort()} a member may use: the bus's half, failure detection's half. */
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

    /** Returns the NATS server URLs of the bus; empty for the embedded JGroups bus. Immutable. */
    public List<String> getNatsServers() {
        return natsServers;
    }

    /** Returns the user name for the NATS servers, if any (then with {@link #getNatsPassword()}). */
    public Optional<String> getNatsUser() {
        return natsUser;
    }

    /** Returns the password for the NATS servers, if any. */
    public Optional<String> getNatsPassword() {
        return natsPassword;
    }

    /** Returns the token for the NATS servers, if any. */
    public Optional<String> getNatsToken() {
        return natsToken;
    }

    /** Returns the NATS credentials file (a user JWT and its nkey seed), if any. */
    public Optional<Path> getNatsCredentialsFile() {
        return natsCredentialsFile;
    }

    /** Returns the file with the nkey seed for the NATS servers, if any. */
    public Optional<Path> getNatsNkeyFile() {
        return natsNkeyFile;
    }

    /** Returns the PEM file of the certificate authorities that TLS to the NATS servers trusts, if any. */
    public Optional<Path> getNatsTlsCaFile() {
        return natsTlsCaFile;
    }

    /** Returns how many replicas the bus's stream gets when this member creates it. */
    public int getNatsReplicas() {
        return natsReplicas;
    }

    @Override
    public String toString() {
        if (!natsServers.isEmpty()) {
            return "DtronOptions[cluster=" + clusterName + memberName.map(n -> ", member=" + n).orElse("")
                    + ", nats=" + natsServers + natsUser.map(u -> ", user=" + u).orElse("")
                    + (natsToken.isPresent() ? ", token" : "")
                    + natsCredentialsFile.map(f -> ", creds=" + f).orElse("")
                    + natsNkeyFile.map(f -> ", nkey=" + f).orElse("") + natsTlsCaFile.map(f -> ", tlsCa=" + f).orElse("")
                    + channels.map(c -> ", channels=" + c.keySet()).orElse("") + (tester ? ", tester" : "")
                    + (clockShift.isZero() ? "" : ", clockShift=" + clockShift) + "]";
        }
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
        private List<String> natsServers = List.of();
        private Optional<String> natsUser = Optional.empty();
        private Optional<String> natsPassword = Optional.empty();
        private Optional<String> natsToken = Optional.empty();
        private Optional<Path> natsCredentialsFile = Optional.empty();
        private Optional<Path> natsNkeyFile = Optional.empty();
        private Optional<Path> natsTlsCaFile = Optional.empty();
        private int natsReplicas = 1;

        private Builder() {
        }

        /**
         * Uses a NATS JetStream bus on these servers instead of the embedded JGroups bus (default: none, JGroups).
         * Each URL is {@code nats://HOST:PORT} or {@code tls://HOST:PORT}; several are servers of one NATS cluster.
         *
         * @throws IllegalArgumentException if a URL has another scheme or no host
         */
        public Builder natsServers(Collection<String> urls) {
            List<String> checked = List.copyOf(urls);
            for (String url : checked) {
                if (!url.matches("(nats|tls)://[^\\s/]+")) {
                    throw new IllegalArgumentException("not a NATS server URL (nats://HOST:PORT or tls://HOST:PORT): '"
                            + url + "'");
                }
            }
            natsServers = checked;
            return this;
        }

        /** Uses a NATS JetStream bus on these servers; see {@link #natsServers(Collection)}. */
        public Builder natsServers(String... urls) {
            return natsServers(List.of(urls));
        }

        /** Authenticates to the NATS servers with a user name and password (default: none). */
        public Builder natsUser(String user, String password) {
            if (Objects.requireNonNull(user, "user").isEmpty() || Objects.requireNonNull(password, "password")
                    .isEmpty()) {
                throw new IllegalArgumentException("NATS user and password must not be empty");
            }
            natsUser = Optional.of(user);
            natsPassword = Optional.of(password);
            return this;
        }

        /** Authenticates to the NATS servers with a token (default: none). */
        public Builder natsToken(String token) {
            if (Objects.requireNonNull(token, "token").isEmpty()) {
                throw new IllegalArgumentException("NATS token is empty");
            }
            natsToken = Optional.of(token);
            return this;
        }

        /** Authenticates to the NATS servers with a credentials file: a user JWT and its nkey seed (default: none). */
        public Builder natsCredentialsFile(Path file) {
            natsCredentialsFile = Optional.of(Objects.requireNonNull(file, "file"));
            return this;
        }

        /** Authenticates to the NATS servers with the nkey seed in a file (default: none). */
        public Builder natsNkeyFile(Path file) {
            natsNkeyFile = Optional.of(Objects.requireNonNull(file, "file"));
            return this;
        }

        /** Talks TLS to the NATS servers, trusting the certificate authorities of a PEM file (default: none). */
        public Builder natsTlsCaFile(Path file) {
            natsTlsCaFile = Optional.of(Objects.requireNonNull(file, "file"));
            return this;
        }

        /**
         * Sets the replicas of the bus's stream, when this member is the first and creates it (default 1): 3 in a
         * cluster of three servers keeps the bus going when one fails.
         */
        public Builder natsReplicas(int replicas) {
            if (replicas < 1 || replicas > 5) {
                throw new IllegalArgumentException("stream replicas must be in 1..5: " + replicas);
            }
            natsReplicas = replicas;
            return this;
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

        /**
         * Sets how many ports above the first a member may use (default {@value DtronOptions#DEFAULT_PORT_RANGE}): the
         * lower half are bus ports (bound to and probed), the upper half failure detection ports; at least 1 over TCP.
         */
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
         * model: a message on any other channel is then rejected as unknown
         * (unless another tester on the bus serves that channel, as the testers
         * of a distributed run serve their models' channels: such a message is
         * only handed to the record listeners), and listeners and sent messages
         * must use these templates.
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
         * @throws IllegalStateException if encryption is on without a secret, the port range exceeds 65535 or is 0
         *                               over TCP, or NATS credentials come without NATS servers
         */
        public DtronOptions build() {
            if (natsServers.isEmpty() && (natsUser.isPresent() || natsToken.isPresent()
                    || natsCredentialsFile.isPresent() || natsNkeyFile.isPresent() || natsTlsCaFile.isPresent())) {
                throw new IllegalStateException("NATS credentials or TLS given without NATS servers");
            }
            if (!natsServers.isEmpty() && inJvm) {
                throw new IllegalStateException("in-JVM mode is for the JGroups bus, not NATS");
            }
            if (encrypt && secret.isEmpty()) {
                throw new IllegalStateException("encryption needs a secret");
            }
            if (port + portRange > 65535) {
                throw new IllegalStateException("ports " + port + ".." + (port + portRange) + " exceed 65535");
            }
            if (portRange < 1 && natsServers.isEmpty() && !inJvm) {
                throw new IllegalStateException("a port range of 0 leaves no port for failure detection: each member"
                        + " listens on two ports (give a port range of 1 or more)");
            }
            return new DtronOptions(this);
        }
    }
}
