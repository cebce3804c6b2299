package io.dtron.api;

import io.dtron.api.internal.TestHooks;
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
 * the bus ports there. A member listens on one port of {@code port .. port+portRange}
 * (the bus ports, all probed): by default 7800..7861, 62 members per address.
 * When no bus port is free, {@link Dtron#connect(DtronOptions)} throws a
 * {@link DtronException} naming the ports in use. For a LAN, give the
 * {@linkplain Builder#bindAddress interface} to bind to and the
 * {@linkplain Builder#initialMembers hosts} where to look for members (each
 * probed over the same bus ports).
 *
 * <p>Only holders of the bus's secret speak on it: every message carries a code
 * made with the secret, and members drop messages without a valid one, so a
 * process without the secret is never a member (see the site's security page).
 * The secret is the {@linkplain Builder#secret one given}, else the content of
 * the {@linkplain Builder#keyFile key file given}, else of the default key file
 * {@code $DTRON_HOME/bus.key} or {@code ~/.dtron/bus.key}, which the first member
 * that needs it creates (mode 600): on one host, members share it with no set-up.
 * {@linkplain Builder#insecure Insecure} members use no secret and talk only to
 * insecure members. {@linkplain Builder#encrypt Encryption} encrypts all traffic
 * with a key derived from the secret. {@linkplain Builder#inJvm In-JVM mode}
 * joins only members of the same JVM, without sockets and without the secret.
 */
public final class DtronOptions {
    /** The cluster name used when none is given. */
    public static final String DEFAULT_CLUSTER = "dtron";
    /** The first port probed and bound to when none is given. */
    public static final int DEFAULT_PORT = 7800;
    /**
     * How many ports above the first are bus ports too when not told otherwise: 61, the bus ports 7800..7861 (62
     * members per address).
     */
    public static final int DEFAULT_PORT_RANGE = 61;

    private final String clusterName;
    private final Optional<String> memberName;
    private final InetAddress bindAddress;
    private final int port;
    private final int portRange;
    private final List<InetSocketAddress> initialMembers;
    private final Optional<String> secret;
    private final Optional<Path> keyFile;
    private final boolean insecure;
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

    static {
        TestHooks.grant((builder, shift) -> builder.clockShift = shift, options -> options.clockShift);
    }

    private DtronOptions(Builder b) {
        clusterName = b.clusterName;
        memberName = b.memberName;
        bindAddress = b.bindAddress;
        port = b.port;
        portRange = b.portRange;
        initialMembers = b.initialMembers;
        secret = b.secret;
        keyFile = b.keyFile;
        insecure = b.insecure;
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

    /** Returns how many ports above {@link #getPort()} are bus ports too. */
    public int getPortRange() {
        return portRange;
    }

    /** Returns where to look for members; empty means at the bind address. Immutable. */
    public List<InetSocketAddress> getInitialMembers() {
        return initialMembers;
    }

    /** Returns the bus's secret, if given; otherwise it is read from the key file. */
    public Optional<String> getSecret() {
        return secret;
    }

    /** Returns the key file holding the bus's secret, if given; otherwise the default key file is used. */
    public Optional<Path> getKeyFile() {
        return keyFile;
    }

    /** Returns whether this member uses no secret: it then talks only to other insecure members. */
    public boolean isInsecure() {
        return insecure;
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
                    + ", nats=" + natsServers + ", " + keyDescription() + natsUser.map(u -> ", user=" + u).orElse("")
                    + (natsToken.isPresent() ? ", token" : "")
                    + natsCredentialsFile.map(f -> ", creds=" + f).orElse("")
                    + natsNkeyFile.map(f -> ", nkey=" + f).orElse("") + natsTlsCaFile.map(f -> ", tlsCa=" + f).orElse("")
                    + channels.map(c -> ", channels=" + c.keySet()).orElse("") + (tester ? ", tester" : "")
                    + (clockShift.isZero() ? "" : ", clockShift=" + clockShift) + "]";
        }
        return "DtronOptions[cluster=" + clusterName + memberName.map(n -> ", member=" + n).orElse("")
                + (inJvm ? ", in-JVM" : ", bind=" + bindAddress.getHostAddress() + ", port=" + port + "+" + portRange
                        + (initialMembers.isEmpty() ? "" : ", initialMembers=" + initialMembers))
                + (inJvm ? "" : ", " + keyDescription()) + ", encrypt=" + encrypt
                + channels.map(c -> ", channels=" + c.keySet()).orElse("") + (tester ? ", tester" : "")
                + (clockShift.isZero() ? "" : ", clockShift=" + clockShift) + "]";
    }

    /** Where the secret comes from, for {@link #toString()}; never the secret itself. */
    private String keyDescription() {
        return insecure ? "INSECURE" : secret.isPresent() ? "secret given" : keyFile.map(f -> "key file " + f)
                .orElse("default key file");
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
        private Optional<Path> keyFile = Optional.empty();
        private boolean insecure;
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
         * Sets how many ports above the first are bus ports too (default {@value DtronOptions#DEFAULT_PORT_RANGE}): a
         * member listens on one of them, and looks for the others on all of them.
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

        /**
         * Sets the bus's secret, which every member of the bus must hold (default: the content of the key file);
         * every message carries a code made with it.
         */
        public Builder secret(String sharedSecret) {
            if (Objects.requireNonNull(sharedSecret, "sharedSecret").isEmpty()) {
                throw new IllegalArgumentException("secret is empty");
            }
            secret = Optional.of(sharedSecret);
            return this;
        }

        /**
         * Reads the bus's secret from this key file when joining (default: {@code $DTRON_HOME/bus.key}, else
         * {@code ~/.dtron/bus.key}, created when missing). The file is never created; joining fails when it is
         * missing, empty, or may be read or written by group or others.
         */
        public Builder keyFile(Path file) {
            keyFile = Optional.of(Objects.requireNonNull(file, "file"));
            return this;
        }

        /**
         * Uses no secret (default: off): this member's messages carry no code that secure members accept, and it
         * accepts only insecure members' messages. For a bus shared with adapters written without the secret; it
         * says so at a warning when it joins.
         */
        public Builder insecure(boolean on) {
            insecure = on;
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
         * Builds the options.
         *
         * @throws IllegalStateException if a secret and a key file are both given, insecure comes with either or with
         *                               encryption, the ports exceed 65535, or NATS credentials come without NATS
         *                               servers
         */
        public DtronOptions build() {
            if (natsServers.isEmpty() && (natsUser.isPresent() || natsToken.isPresent()
                    || natsCredentialsFile.isPresent() || natsNkeyFile.isPresent() || natsTlsCaFile.isPresent())) {
                throw new IllegalStateException("NATS credentials or TLS given without NATS servers");
            }
            if (!natsServers.isEmpty() && inJvm) {
                throw new IllegalStateException("in-JVM mode is for the JGroups bus, not NATS");
            }
            if (secret.isPresent() && keyFile.isPresent()) {
                throw new IllegalStateException("give the bus's secret or its key file, not both");
            }
            if (insecure && (secret.isPresent() || keyFile.isPresent() || encrypt)) {
                throw new IllegalStateException("an insecure member has no secret: leave out the secret, the key file"
                        + " and encryption");
            }
            if (encrypt && inJvm && secret.isEmpty()) {
                throw new IllegalStateException("encryption of in-JVM members needs a secret");
            }
            if (port + portRange > 65535) {
                throw new IllegalStateException("ports " + port + ".." + (port + portRange) + " exceed 65535");
            }
            return new DtronOptions(this);
        }
    }
}
