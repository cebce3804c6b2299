package io.dtron.bus.internal;

import java.io.DataInput;
import java.io.EOFException;
import java.net.InetAddress;
import java.security.GeneralSecurityException;
import java.security.MessageDigest;
import java.util.Arrays;
import java.util.Collection;
import java.util.HashSet;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.LongAdder;
import javax.crypto.Mac;
import javax.crypto.ShortBufferException;
import javax.crypto.spec.SecretKeySpec;
import org.jgroups.Address;
import org.jgroups.blocks.cs.Connection;
import org.jgroups.stack.IpAddress;
import org.jgroups.protocols.TCP;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. JGroups' TCP transport with every frame it sends carrying a code, and every frame it reads checked before
 * anything is parsed from it or allocated for it.
 *
 * <p><b>Codes.</b> A frame is the bytes JGroups puts on the wire for one message (version, flags, destination,
 * source, headers and payload, discovery and membership messages and heartbeats alike); this transport appends
 * {@code HMAC-SHA256(K, frame)} (32 bytes) to it, with {@code K} the bus's code key ({@link BusKeys#macKey}). A
 * frame read from a connection is dropped, unparsed, unless it ends in the code of the bytes before it: so a
 * process without the secret is never seen as a member. It cannot take part in discovery, join, answer as a
 * coordinator, merge, or send a heartbeat or a message that any member reads; it can neither delay nor split the
 * members that hold the secret, even when it started first on their ports. Only whole frames are checked, so codes
 * cost one HMAC of a small buffer per frame sent and per frame read: microseconds. A frame sent to several members
 * is coded once per member.
 *
 * <p><b>Lengths.</b> A frame announcing less than a code's length or more than {@value #MAX_FRAME} bytes (FRAG2
 * cuts DTRON's messages into fragments of 60,000 bytes) ends its connection before anything is allocated for it;
 * a frame is read into a buffer of its announced length and parsed from there, so no length inside an unchecked
 * frame is ever believed. A dropped frame or connection is counted ({@link #rejectedFrames()}); the first from each
 * host is logged as one line, once for all members of the bus in this JVM, without a stack trace, and the
 * connection is closed quietly (as a peer's close is).
 *
 * <p><b>Connections.</b> Connections carry no peer address (JGroups' "peer connections" are off): a member sends on
 * the connections it opened to the others' bus ports, and reads on those the others opened to it, each known by its
 * socket's address. A process that claims a member's address when it connects therefore cannot take the place of
 * that member's connection. A member whose connection closes without JGroups' graceful close (its process died)
 * is suspected at once (JGroups' {@code enable_suspect_events}), which VERIFY_SUSPECT2 confirms over the bus.
 */
public final class GuardedTcp extends TCP {
    /** The largest frame read, code included. */
    static final int MAX_FRAME = 256 * 1024;
    /** The length of a code: HMAC-SHA256. */
    static final int CODE_LENGTH = 32;
    /** The smallest frame JGroups reads: version (2) and flags (1). */
    private static final int MIN_MESSAGE = 3;
    private static final String HMAC = "HmacSHA256";
    private static final Logger LOG = LoggerFactory.getLogger(GuardedTcp.class);

    private final SecretKeySpec key;
    private final ThreadLocal<Mac> macs;
    private final LongAdder rejected = new LongAdder();
    /** The bus and host of every dropped frame logged in this JVM: its members of one bus log each host once. */
    private static final Set<String> NAMED = ConcurrentHashMap.newKeySet();
    private final Set<Address> incoming = ConcurrentHashMap.newKeySet();
    private final String busName;

    /** A transport whose codes are made with the code key {@code macKey}; {@code busName} names the bus in logs. */
    GuardedTcp(byte[] macKey, String busName) {
        this.key = new SecretKeySpec(macKey.clone(), HMAC);
        this.busName = busName;
        this.macs = ThreadLocal.withInitial(this::newMac);
        enableSuspectEvents(true);
    }

    private Mac newMac() {
        try {
            Mac mac = Mac.getInstance(HMAC);
            mac.init(key);
            return mac;
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("HMAC-SHA256 is missing from this Java runtime", e);
        }
    }

    /** Returns how many frames and connections this transport dropped for a missing or wrong code or length. */
    public long rejectedFrames() {
        return rejected.sum();
    }

    @Override
    public void start() throws Exception {
        super.start();
        // see the class comment: a connection is known by its socket's address, not by one its peer claims
        srv.usePeerConnections(false);
    }

    /** Notes the connections other members opened to this one: their keys are their sockets' addresses. */
    @Override
    public void connectionEstablished(Connection conn) {
        super.connectionEstablished(conn);
        Address local = conn.localAddress();
        if (local instanceof IpAddress ip && ip.getPort() == getBindPort()) {
            incoming.add(conn.peerAddress());
        }
    }

    @Override
    public void connectionClosed(Connection conn) {
        incoming.remove(conn.peerAddress());
        super.connectionClosed(conn);
    }

    /**
     * Closes the connections this member opened to members that left, as JGroups does at every view; keeps the
     * connections other members opened to it (which JGroups, knowing only members' addresses, would close too): their
     * peers close them when they leave, or they end when their processes die.
     */
    @Override
    public void retainAll(Collection<Address> members) {
        Set<Address> keep = new HashSet<>(members);
        keep.addAll(incoming);
        super.retainAll(keep);
    }

    @Override
    public void send(Address dest, byte[] data, int offset, int length) throws Exception {
        byte[] frame = Arrays.copyOfRange(data, offset, offset + length + CODE_LENGTH);
        Mac mac = macs.get();
        mac.update(frame, 0, length);
        try {
            mac.doFinal(frame, length);
        } catch (ShortBufferException e) {
            throw new IllegalStateException("no room for the code", e);
        }
        super.send(dest, frame, 0, frame.length);
    }

    /** A frame read from a connection: checked, then parsed (see the class comment). */
    @Override
    public void receive(Address sender, DataInput in, int length) throws Exception {
        if (length < MIN_MESSAGE + CODE_LENGTH || length > MAX_FRAME) {
            reject(sender, "announced " + Integer.toUnsignedString(length) + " bytes");
            throw new DroppedConnection();
        }
        byte[] frame = new byte[length];
        in.readFully(frame);
        if (!valid(frame, 0, length)) {
            reject(sender, "carried no valid code");
            throw new DroppedConnection();
        }
        super.receive(sender, frame, 0, length - CODE_LENGTH);
    }

    /** A frame this member sent to itself through its server. */
    @Override
    public void receive(Address sender, byte[] data, int offset, int length) {
        if (length < MIN_MESSAGE + CODE_LENGTH || !valid(data, offset, length)) {
            reject(sender, "carried no valid code");
            return;
        }
        super.receive(sender, data, offset, length - CODE_LENGTH);
    }

    private boolean valid(byte[] data, int offset, int length) {
        Mac mac = macs.get();
        mac.update(data, offset, length - CODE_LENGTH);
        byte[] expected = mac.doFinal();
        return MessageDigest.isEqual(expected, Arrays.copyOfRange(data, offset + length - CODE_LENGTH,
                offset + length));
    }

    private void reject(Address sender, String what) {
        rejected.increment();
        String host = host(sender);
        if (NAMED.add(busName + "\n" + host)) {
            LOG.warn("Bus '{}': dropped a frame from {} that {}, as every frame without this bus's code is dropped"
                    + " (its sender lacks the bus's secret, or one of the two was started with --insecure); not logged"
                    + " again for host {}", busName, sender == null ? "a connection" : sender, what, host);
        }
    }

    private static String host(Address sender) {
        if (sender instanceof IpAddress ip) {
            InetAddress address = ip.getIpAddress();
            return address == null ? "" : address.getHostAddress();
        }
        return String.valueOf(sender);
    }

    /** Ends a connection quietly: JGroups closes a connection whose reader meets the end of its stream unlogged. */
    private static final class DroppedConnection extends EOFException {
        private static final long serialVersionUID = 1L;

        DroppedConnection() {
            super("frame dropped");
        }
    }
}
