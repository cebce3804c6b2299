package io.dtron.bus.internal;

import java.nio.charset.StandardCharsets;
import java.security.GeneralSecurityException;
import java.util.ArrayList;
import java.util.List;
import javax.crypto.SecretKey;
import javax.crypto.SecretKeyFactory;
import javax.crypto.spec.PBEKeySpec;
import javax.crypto.spec.SecretKeySpec;
import org.jgroups.protocols.FD_ALL3;
import org.jgroups.protocols.FRAG2;
import org.jgroups.protocols.MERGE3;
import org.jgroups.protocols.MFC;
import org.jgroups.protocols.SEQUENCER;
import org.jgroups.protocols.SHARED_LOOPBACK;
import org.jgroups.protocols.SHARED_LOOPBACK_PING;
import org.jgroups.protocols.SYM_ENCRYPT;
import org.jgroups.protocols.TCPPING;
import org.jgroups.protocols.UFC;
import org.jgroups.protocols.UNICAST3;
import org.jgroups.protocols.VERIFY_SUSPECT2;
import org.jgroups.protocols.pbcast.GMS;
import org.jgroups.protocols.pbcast.NAKACK2;
import org.jgroups.protocols.pbcast.STABLE;
import org.jgroups.stack.Protocol;

/**
 * Not API. Builds DTRON's JGroups protocol stack in code, bottom (transport) first.
 *
 * <pre>
 *  GuardedTcp (bind address, one bus port)   | SHARED_LOOPBACK        (in-JVM mode)
 *  TCPPING (initial members, the bus ports)  | SHARED_LOOPBACK_PING
 *  MERGE3                                      heals partitions
 *  FD_ALL3, VERIFY_SUSPECT2                    failure detection (with GuardedTcp's closed connections)
 *  SYM_ENCRYPT                                 optional: AES, key derived from the secret
 *  NAKACK2, UNICAST3, STABLE                   reliable FIFO multicast and unicast
 *  GMS                                         membership views
 *  MFC, UFC                                    flow control
 *  SEQUENCER                                   total order: every multicast goes through the coordinator
 *  FRAG2                                       large messages
 * </pre>
 *
 * <p><b>Ports.</b> A member listens on one socket, on the bind address (none on
 * the wildcard address), at a bus port of {@code port..port+range}, which
 * {@link JGroupsTransport} picks. JGroups' diagnostics (a UDP listener) stay
 * off, as JGroups' default has them.
 *
 * <p><b>The bus's secret.</b> Over TCP every frame carries a code made with the
 * bus's secret, and every frame read is checked, and its length bounded, before
 * anything is parsed from it ({@link GuardedTcp}): discovery, joins, merges,
 * heartbeats and messages of a process without the secret never reach a
 * protocol. That makes JGroups' AUTH redundant (a join request without the
 * secret never reaches GMS), so the stack has none. Failure detection has no
 * sockets of its own: FD_SOCK2 listened on a second port and read frames
 * without codes; instead a member whose TCP connection closes without JGroups'
 * graceful close (its process died) is suspected at once, VERIFY_SUSPECT2
 * confirms it over the guarded bus within 1.5 s, and FD_ALL3's heartbeats find
 * a member that hangs within 15 s. In-JVM members have no sockets and no codes.
 *
 * <p><b>Discovery.</b> Members find each other with TCPPING over the bus ports:
 * every member listens on a free bus port and
 * probes all bus ports at each initial member (by default only the bind
 * address, i.e. 127.0.0.1). On one host this needs no configuration, no
 * multicast (often unavailable on loopback in containers and sandboxes), no
 * shared directory and no daemon; probing a closed loopback port fails at
 * once. On a LAN, the same range is probed at every given initial member
 * (a connection attempt gives up after 300 ms). Members of other clusters in
 * the range answer nothing: JGroups drops messages whose cluster name differs,
 * and members with another secret (or none) are dropped before that.
 * The bus ports bound how many members one address can hold (62 by default).
 * Alternatives that were not taken: UDP multicast discovery (blocked in many
 * sandboxes and containers, even on loopback) and FILE_PING (needs a
 * directory shared by all users of the bus and leaves stale entries of
 * crashed members behind).
 *
 * <p><b>Latency.</b> TCP_NODELAY, no bundler (the sending thread writes the
 * message) and the "direct" message processing policy (the reading thread
 * passes regular messages up): each hop costs one thread wake-up.
 *
 * <p><b>In-JVM mode</b> uses SHARED_LOOPBACK: the members of one JVM exchange
 * messages in memory, with no sockets at all, with no bundler and direct
 * processing as over TCP. That also keeps a leaving member's last messages
 * ahead of the view without it: with a bundler thread, the sequencer's
 * broadcast of a message could still be queued when the member's leave
 * request installed the new view.
 */
final class JGroupsStack {
    private static final int PBKDF2_ITERATIONS = 65_536;
    private static final int AES_KEY_BITS = 128;
    private static final String NO_BUNDLER = "no-bundler";
    private static final String DIRECT = "direct";

    private JGroupsStack() {
    }

    /** Returns the stack of a member; over TCP, its bus port is {@code busPort} (in JGroupsSettings' bus ports). */
    static List<Protocol> build(JGroupsSettings settings, int busPort) {
        List<Protocol> stack = new ArrayList<>();
        if (settings.inJvm()) {
            SHARED_LOOPBACK loopback = new SHARED_LOOPBACK();
            loopback.setBundlerType(NO_BUNDLER);
            loopback.setMessageProcessingPolicy(DIRECT);
            stack.add(loopback.logDiscardMsgs(false));
            stack.add(new SHARED_LOOPBACK_PING());
        } else {
            GuardedTcp tcp = new GuardedTcp(settings.macKey(), settings.clusterName());
            tcp.setSockConnTimeout(300);
            // without TCP_NODELAY, Nagle's algorithm holds small messages back until the previous one is
            // acknowledged, and with delayed acknowledgements that costs up to 40 ms per message
            tcp.tcpNodelay(true);
            // DTRON's messages are few and small, and their latency is what a test measures: every message is
            // written by the thread that sends it (no bundler thread to wake) and passed up by the thread that
            // reads it from the socket (no thread-pool hand-off). On loopback this took p99 of one hop from
            // about 3 ms to about 0.35 ms (src/site/markdown/benchmarks.md).
            tcp.setBundlerType(NO_BUNDLER);
            tcp.setMessageProcessingPolicy(DIRECT);
            // GuardedTcp puts a buffer of its own on each connection, one that closes quietly (see its quietInput)
            tcp.setBufferedInputStreamSize(0);
            stack.add(tcp
                    .setBindAddress(settings.bindAddress())
                    .setBindPort(busPort)
                    .setPortRange(0)
                    .logDiscardMsgs(false));
            // TCPPING applies its own port_range only to hosts given as a string, so the range is expanded here
            stack.add(new TCPPING().setInitialHosts(settings.discoveryAddresses()).setPortRange(0));
        }
        stack.add(new MERGE3().setMinInterval(1_000).setMaxInterval(5_000));
        stack.add(new FD_ALL3().setTimeout(15_000).setInterval(3_000));
        stack.add(new VERIFY_SUSPECT2().setTimeout(1_500));
        settings.secret().filter(secret -> settings.encrypt()).ifPresent(secret -> {
            SYM_ENCRYPT encrypt = new SYM_ENCRYPT().symAlgorithm("AES/CBC/PKCS5Padding").symIvLength(16);
            stack.add(encrypt.setSecretKey(deriveKey(secret, settings.clusterName())));
        });
        stack.add(new NAKACK2().useMcastXmit(false));
        stack.add(new UNICAST3());
        stack.add(new STABLE());
        stack.add(new GMS().printLocalAddress(false).setJoinTimeout(1_000));
        stack.add(new MFC());
        stack.add(new UFC());
        stack.add(new SEQUENCER());
        stack.add(new FRAG2().setFragSize(60_000));
        return stack;
    }

    /** Derives the AES key from the secret with PBKDF2, salted with the cluster name. */
    static SecretKey deriveKey(String secret, String clusterName) {
        try {
            PBEKeySpec spec = new PBEKeySpec(secret.toCharArray(),
                    ("dtron-bus:" + clusterName).getBytes(StandardCharsets.UTF_8), PBKDF2_ITERATIONS, AES_KEY_BITS);
            byte[] key = SecretKeyFactory.getInstance("PBKDF2WithHmacSHA256").generateSecret(spec).getEncoded();
            spec.clearPassword();
            return new SecretKeySpec(key, "AES");
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("cannot derive the encryption key", e);
        }
    }
}
