package io.dtron.bus.internal;

import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.regex.Pattern;

/**
 * Not API. What a {@link NatsTransport} needs to know to join its bus.
 *
 * @param busName         the bus (the cluster name): stream {@code DTRON_<bus>}, subjects {@code dtron.<bus>.>}
 * @param memberName      this member's id, unique on the bus
 * @param servers         the NATS server URLs ({@code nats://HOST:PORT}, {@code tls://HOST:PORT}), at least one
 * @param user            user name for user/password authentication, with {@code password}
 * @param password        password for user/password authentication
 * @param token           token for token authentication
 * @param credentialsFile a NATS credentials file (JWT and nkey seed)
 * @param nkeyFile        a file holding an nkey seed ({@code SU...}) for nkey authentication
 * @param tlsCaFile       a PEM file of the certificate authorities to trust: TLS to the servers
 * @param replicas        the stream's replicas, when this member creates it (1, or up to 5 in a cluster)
 * @param macKey          the key K of the messages' codes ({@link BusKeys#macKey}, 32 bytes); empty for an insecure
 *                        member
 */
public record NatsSettings(
        String busName,
        String memberName,
        List<String> servers,
        Optional<String> user,
        Optional<String> password,
        Optional<String> token,
        Optional<Path> credentialsFile,
        Optional<Path> nkeyFile,
        Optional<Path> tlsCaFile,
        int replicas,
        Optional<byte[]> macKey) {

    /** Bus names: one NATS subject token that is also a stream name. */
    public static final Pattern BUS_NAME = Pattern.compile("[A-Za-z0-9_-]{1,64}");
    /** Member ids: they travel in a message header. */
    public static final Pattern MEMBER_NAME = Pattern.compile("[\\x21-\\x7E]{1,128}");
    /** How often a member says it is alive. */
    public static final Duration HEARTBEAT = Duration.ofSeconds(1);
    /** How long a member may stay silent in the stream before the others take it as gone. */
    public static final Duration SILENCE = Duration.ofSeconds(4);
    /**
     * How long a member may receive nothing from the stream, its own heartbeats included, before it takes its
     * consumer for stuck and makes it anew.
     */
    public static final Duration STALL = Duration.ofSeconds(5);
    /** How long the stream keeps a message. */
    public static final Duration MAX_AGE = Duration.ofMinutes(10);
    /** How many bytes the stream keeps at most; the oldest messages go first. */
    public static final long MAX_BYTES = 64L * 1024 * 1024;
    /** For how long the stream recognises a message published twice (a retry after a server failed). */
    public static final Duration DUPLICATE_WINDOW = Duration.ofMinutes(1);

    /** Checks the settings and makes them immutable. */
    public NatsSettings {
        Objects.requireNonNull(busName, "busName");
        Objects.requireNonNull(memberName, "memberName");
        servers = List.copyOf(servers);
        Objects.requireNonNull(user, "user");
        Objects.requireNonNull(password, "password");
        Objects.requireNonNull(token, "token");
        Objects.requireNonNull(credentialsFile, "credentialsFile");
        Objects.requireNonNull(nkeyFile, "nkeyFile");
        Objects.requireNonNull(tlsCaFile, "tlsCaFile");
        if (!BUS_NAME.matcher(busName).matches()) {
            throw new IllegalArgumentException("a NATS bus name is 1 to 64 letters, digits, '_' or '-': '" + busName
                    + "'");
        }
        if (!MEMBER_NAME.matcher(memberName).matches()) {
            throw new IllegalArgumentException("a member id on a NATS bus is 1 to 128 printable characters without"
                    + " spaces: '" + memberName + "'");
        }
        if (servers.isEmpty()) {
            throw new IllegalArgumentException("no NATS server given");
        }
        if (user.isPresent() != password.isPresent()) {
            throw new IllegalArgumentException("a NATS user needs a password, and a password a user");
        }
        if (replicas < 1 || replicas > 5) {
            throw new IllegalArgumentException("stream replicas must be in 1..5: " + replicas);
        }
        macKey = Objects.requireNonNull(macKey, "macKey").map(byte[]::clone);
    }

    /** Returns a copy of the key of the messages' codes, if this member is not insecure. */
    @Override
    public Optional<byte[]> macKey() {
        return macKey.map(byte[]::clone);
    }

    /** The stream of the bus. */
    public String streamName() {
        return "DTRON_" + busName;
    }

    /** The subjects of the bus's stream. */
    public String streamSubjects() {
        return "dtron." + busName + ".>";
    }

    /** The subject of a channel's messages. */
    public String channelSubject(String group) {
        return "dtron." + busName + ".c." + group;
    }

    /** The subject of the members' presence messages. */
    public String presenceSubject() {
        return "dtron." + busName + ".p";
    }

    @Override
    public String toString() {
        return "NatsSettings[bus=" + busName + ", member=" + memberName + ", servers=" + servers
                + (user.isPresent() ? ", user=" + user.get() : "") + (token.isPresent() ? ", token" : "")
                + credentialsFile.map(f -> ", creds=" + f).orElse("") + nkeyFile.map(f -> ", nkey=" + f).orElse("")
                + tlsCaFile.map(f -> ", tlsCa=" + f).orElse("") + ", replicas=" + replicas
                + (macKey.isPresent() ? ", secure" : ", INSECURE") + "]";
    }
}
