package io.dtron.bus.internal;

import java.io.BufferedInputStream;
import java.io.DataInput;
import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.InputStream;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.net.InetAddress;
import java.net.SocketException;
import java.nio.charset.StandardCharsets;
import java.security.GeneralSecurityException;
import java.security.MessageDigest;
import java.security.SecureRandom;
import java.util.ArrayDeque;
import java.util.Arrays;
import java.util.Collection;
import java.util.EnumMap;
import java.util.HashSet;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.LongAdder;
import javax.crypto.Mac;
import javax.crypto.ShortBufferException;
import javax.crypto.spec.SecretKeySpec;
import org.jgroups.Address;
import org.jgroups.blocks.cs.Connection;
import org.jgroups.blocks.cs.TcpConnection;
import org.jgroups.protocols.TCP;
import org.jgroups.stack.IpAddress;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. JGroups' TCP transport with every connection bound to a fresh pair of nonces, every frame it sends
 * carrying a code of its connection and its place in it, and every frame it reads checked before anything is
 * parsed from it or allocated for it. security.md ("Over JGroups") is the specification.
 *
 * <p><b>Handshake.</b> A member that accepts a connection first writes a challenge on it: {@code "DTC1"} and 16
 * random bytes {@code nB}. The member that opened it answers, before any frame, with a hello: {@code "DTH1"}, 16
 * random bytes {@code nA}, {@code HMAC(K, "DTH1" nA)} (it holds the secret) and {@code HMAC(K, "DTH1" nA nB)} (for
 * this connection), with {@code K} the bus's code key ({@link BusKeys#macKey}). Both then code the connection's
 * frames with {@code Kc = HMAC(K, "dtron-bus-conn-v1" nA nB)}. Frames the opener sends before the challenge came
 * wait for it (up to {@value #PENDING_LIMIT} bytes; later ones are dropped, as a lost frame, which JGroups sends
 * again), so that a port that never answers holds no sender up.
 *
 * <p><b>Codes.</b> A frame is the bytes JGroups puts on the wire for one message (version, flags, destination,
 * source, headers and payload, discovery and membership messages and heartbeats alike); the n-th frame of a
 * connection (from 0) carries {@code HMAC(Kc, 0x01 n frame)} (32 bytes; {@code n} as 8 bytes, big-endian; 0x01: from
 * the opener to the acceptor, the only way frames go, as a member sends on the connections it opened). A frame read
 * is dropped, unparsed, unless it ends in the code for its connection and its place there: so a process without the
 * secret is never seen as a member (it cannot take part in discovery, join, answer as a coordinator, merge, or send
 * a heartbeat or a message that any member reads, nor delay or split the members, even when it started first on
 * their ports), and a frame recorded on the network and sent again, on another connection, twice or out of its
 * order, is dropped too. A hello with a valid proof of the secret made for another connection is counted as
 * {@link DropReason#REPLAYED}, everything else as {@link DropReason#UNAUTHENTICATED}. Codes cost one HMAC of a
 * small buffer per frame sent and per frame read: below a microsecond.
 *
 * <p><b>Lengths.</b> The first frame of a connection must be the challenge (to the opener) or the hello (to the
 * acceptor), of their exact lengths; then a frame announcing less than a code's length or more than
 * {@value #MAX_FRAME} bytes (FRAG2 cuts DTRON's messages into fragments of 60,000 bytes) ends its connection before
 * anything is allocated for it; a frame is read into a buffer of its announced length and parsed from there, so no
 * length inside an unchecked frame is ever believed. A dropped frame ends its connection and is counted
 * ({@link #drops()}); the first of each reason from each host is logged as one line, once for all members of the
 * bus in this JVM, without a stack trace, and the connection is closed quietly (as a peer's close is).
 *
 * <p><b>Connections.</b> Connections carry no peer address (JGroups' "peer connections" are off): a member sends on
 * the connections it opened to the others' bus ports, and reads on those the others opened to it, each known by its
 * socket's address. A process that claims a member's address when it connects therefore cannot take the place of
 * that member's connection. A member whose connection closes without JGroups' graceful close (its process died)
 * is suspected at once (JGroups' {@code enable_suspect_events}), which VERIFY_SUSPECT2 confirms over the bus.
 * A member leaving leaves no warning nor error in any member's log: connections are read through a buffer that
 * closes quietly ({@code quietInput}), and JGroups' failure to write its graceful close on a connection both ends
 * closed at once is logged at debug level ({@code ClosingQuietLog}).
 */
public final class GuardedTcp extends TCP {
    /** The largest frame read, code included. */
    static final int MAX_FRAME = 256 * 1024;
    /** The length of a code: HMAC-SHA256. */
    static final int CODE_LENGTH = 32;
    /** The length of a nonce. */
    static final int NONCE_LENGTH = 16;
    /** A challenge: its tag and the acceptor's nonce. */
    static final int CHALLENGE_LENGTH = 4 + NONCE_LENGTH;
    /** A hello: its tag, the opener's nonce, the proof of the secret and the proof for the connection. */
    static final int HELLO_LENGTH = 4 + NONCE_LENGTH + 2 * CODE_LENGTH;
    /** How many bytes of frames an opener keeps while it waits for its connection's challenge. */
    static final int PENDING_LIMIT = 1024 * 1024;
    static final byte[] CHALLENGE_TAG = "DTC1".getBytes(StandardCharsets.US_ASCII);
    static final byte[] HELLO_TAG = "DTH1".getBytes(StandardCharsets.US_ASCII);
    private static final byte[] CONNECTION_KEY_LABEL = "dtron-bus-conn-v1".getBytes(StandardCharsets.US_ASCII);
    /** The direction of frames, from the member that opened a connection to the one that accepted it. */
    private static final byte TO_ACCEPTOR = 1;
    /** The smallest frame JGroups reads: version (2) and flags (1). */
    private static final int MIN_MESSAGE = 3;
    private static final String HMAC = "HmacSHA256";
    private static final Logger LOG = LoggerFactory.getLogger(GuardedTcp.class);
    /** The bus, host and reason of every dropped frame logged in this JVM: its members of one bus log each once. */
    private static final Set<String> NAMED = ConcurrentHashMap.newKeySet();
    private static final VarHandle CONNECTION_INPUT = connectionInput();

    private final byte[] macKey;
    private final ThreadLocal<Mac> macs;
    private final SecureRandom random = new SecureRandom();
    private final Map<DropReason, LongAdder> drops = new EnumMap<>(DropReason.class);
    /** The connections other members opened to this one, by the streams their frames are read from. */
    private final Map<DataInput, Accepted> accepted = new ConcurrentHashMap<>();
    /** The connections this member opened, by the streams their challenges are read from. */
    private final Map<DataInput, Opened> openedByInput = new ConcurrentHashMap<>();
    /** The connections this member opened, by themselves (JGroups may keep several to one member for a while). */
    private final Map<Connection, Opened> opened = new ConcurrentHashMap<>();
    private final String busName;

    /** A transport whose codes are made with the code key {@code macKey}; {@code busName} names the bus in logs. */
    GuardedTcp(byte[] macKey, String busName) {
        this.macKey = macKey.clone();
        this.busName = busName;
        this.macs = ThreadLocal.withInitial(() -> newMac(this.macKey));
        for (DropReason reason : DropReason.values()) {
            drops.put(reason, new LongAdder());
        }
        enableSuspectEvents(true);
    }

    static Mac newMac(byte[] key) {
        try {
            Mac mac = Mac.getInstance(HMAC);
            mac.init(new SecretKeySpec(key, HMAC));
            return mac;
        } catch (GeneralSecurityException e) {
            throw new IllegalStateException("HMAC-SHA256 is missing from this Java runtime", e);
        }
    }

    /** Returns how many frames (each ending its connection) this transport dropped. */
    public long rejectedFrames() {
        return drops.values().stream().mapToLong(LongAdder::sum).sum();
    }

    /** Returns how many frames this transport dropped, by reason. */
    public Map<DropReason, Long> drops() {
        Map<DropReason, Long> counts = new EnumMap<>(DropReason.class);
        drops.forEach((reason, count) -> counts.put(reason, count.sum()));
        return counts;
    }

    @Override
    public void start() throws Exception {
        super.start();
        // see the class comment: a connection is known by its socket's address, not by one its peer claims
        srv.usePeerConnections(false);
        srv.log(new ClosingQuietLog(log));
    }

    /**
     * A new connection, before its reader starts: one another member opened gets this member's challenge at once;
     * one this member opened waits for the challenge of the member it goes to.
     */
    @Override
    public void connectionEstablished(Connection conn) {
        super.connectionEstablished(conn);
        Address local = conn.localAddress();
        DataInput in = quietInput(conn);
        if (local instanceof IpAddress ip && ip.getPort() == getBindPort()) {
            Accepted connection = new Accepted(conn, nonce());
            accepted.put(in, connection);
            byte[] challenge = concat(CHALLENGE_TAG, connection.nonce);
            try {
                conn.send(challenge, 0, challenge.length);
            } catch (Exception e) {
                // the peer is gone already: its connection ends when its reader finds the socket closed
                closeQuietly(conn);
            }
        } else {
            Opened connection = new Opened(conn, nonce());
            openedByInput.put(in, connection);
            opened.put(conn, connection);
        }
    }

    @Override
    public void connectionClosed(Connection conn) {
        DataInput in = input(conn);
        if (in != null) { // null: the connection closed before it was connected
            accepted.remove(in);
            openedByInput.remove(in);
        }
        opened.remove(conn);
        super.connectionClosed(conn);
    }

    /**
     * The stream a connection's frames are read from, which {@link #receive(Address, DataInput, int)} is called with:
     * it tells the connection apart from others to the same address (JGroups keeps a connection to a member it
     * no longer knows by its address open until it closes).
     */
    private static DataInput input(Connection conn) {
        return (DataInput) CONNECTION_INPUT.get((TcpConnection) conn);
    }

    /**
     * Puts a buffer that closes quietly between a new connection and its socket (before its reader starts), and
     * returns the connection's new stream. JGroups' own buffer (turned off in {@link JGroupsStack}) failed its reader
     * with "Stream closed", which JGroups logs as a WARN with a stack trace, when the thread that closes the
     * connection (installing a view without its peer) closed it as the reader was taking the peer's end of stream:
     * whenever a member left. This one fails it as a closed socket does, which JGroups takes quietly.
     */
    private static DataInput quietInput(Connection conn) {
        DataInputStream socket = (DataInputStream) CONNECTION_INPUT.get((TcpConnection) conn);
        DataInputStream quiet = new DataInputStream(new QuietBuffer(socket));
        CONNECTION_INPUT.set((TcpConnection) conn, quiet);
        return quiet;
    }

    private static VarHandle connectionInput() {
        try {
            return MethodHandles.privateLookupIn(TcpConnection.class, MethodHandles.lookup())
                    .findVarHandle(TcpConnection.class, "in", DataInputStream.class);
        } catch (ReflectiveOperationException e) {
            throw new IllegalStateException("this JGroups has no TcpConnection.in: DTRON needs the version it was"
                    + " built with", e);
        }
    }

    /**
     * Closes the connections this member opened to members that left, as JGroups does at every view; keeps the
     * connections other members opened to it (which JGroups, knowing only members' addresses, would close too): their
     * peers close them when they leave, or they end when their processes die.
     */
    @Override
    public void retainAll(Collection<Address> members) {
        Set<Address> keep = new HashSet<>(members);
        accepted.values().forEach(connection -> keep.add(connection.connection.peerAddress()));
        super.retainAll(keep);
    }

    @Override
    public void send(Address dest, byte[] data, int offset, int length) throws Exception {
        if (dest == null || dest.equals(srv.localAddress())) {
            return; // JGroups' transport drops what it sends itself (it passed it up already); it sends to members
        }
        byte[] frame = Arrays.copyOfRange(data, offset, offset + length + CODE_LENGTH);
        Connection conn = srv.getConnection(dest);
        try {
            Opened out = opened.get(conn);
            if (out == null) {
                throw new SocketException("the connection to " + dest + " closed");
            }
            out.send(frame);
        } catch (Exception e) {
            srv.removeConnectionIfPresent(dest, conn);
            throw e;
        }
    }

    /** A frame read from a connection: checked, then parsed (see the class comment). */
    @Override
    public void receive(Address sender, DataInput in, int length) throws Exception {
        Accepted from = accepted.get(in);
        if (from != null) {
            receiveAccepted(from, sender, in, length);
            return;
        }
        Opened to = openedByInput.get(in);
        if (to == null) {
            throw new DroppedConnection(); // its connection closed while this frame was read: nothing to judge
        }
        if (length != CHALLENGE_LENGTH || to.challenged()) {
            throw drop(sender, DropReason.UNAUTHENTICATED, "broke the handshake");
        }
        byte[] challenge = new byte[CHALLENGE_LENGTH];
        in.readFully(challenge);
        if (!MessageDigest.isEqual(CHALLENGE_TAG, Arrays.copyOf(challenge, CHALLENGE_TAG.length))) {
            throw drop(sender, DropReason.UNAUTHENTICATED, "broke the handshake");
        }
        try {
            to.challenge(Arrays.copyOfRange(challenge, CHALLENGE_TAG.length, CHALLENGE_LENGTH));
        } catch (Exception e) {
            throw new DroppedConnection(); // the connection closed while the hello went out
        }
    }

    private void receiveAccepted(Accepted from, Address sender, DataInput in, int length) throws Exception {
        Link link = from.link;
        if (link == null) {
            if (length != HELLO_LENGTH) {
                throw drop(sender, DropReason.UNAUTHENTICATED, length < 0 || length > MAX_FRAME
                        ? "announced " + Integer.toUnsignedString(length) + " bytes" : "carried no valid code");
            }
            byte[] hello = new byte[HELLO_LENGTH];
            in.readFully(hello);
            from.link = hello(hello, from.nonce, sender);
            return;
        }
        if (length < MIN_MESSAGE + CODE_LENGTH || length > MAX_FRAME) {
            throw drop(sender, DropReason.UNAUTHENTICATED, "announced " + Integer.toUnsignedString(length) + " bytes");
        }
        byte[] frame = new byte[length];
        in.readFully(frame);
        if (!link.check(frame, length - CODE_LENGTH)) {
            throw drop(sender, DropReason.UNAUTHENTICATED, "carried no valid code for its place in its connection");
        }
        super.receive(sender, frame, 0, length - CODE_LENGTH);
    }

    /** Checks a hello on a connection whose challenge was {@code acceptorNonce}; returns the connection's link. */
    private Link hello(byte[] hello, byte[] acceptorNonce, Address sender) throws DroppedConnection {
        int tagged = HELLO_TAG.length + NONCE_LENGTH;
        Mac mac = macs.get();
        mac.update(hello, 0, tagged);
        boolean tag = MessageDigest.isEqual(HELLO_TAG, Arrays.copyOf(hello, HELLO_TAG.length));
        if (!tag || !MessageDigest.isEqual(mac.doFinal(), Arrays.copyOfRange(hello, tagged, tagged + CODE_LENGTH))) {
            throw drop(sender, DropReason.UNAUTHENTICATED, "carried no valid code");
        }
        mac.update(hello, 0, tagged);
        mac.update(acceptorNonce);
        if (!MessageDigest.isEqual(mac.doFinal(), Arrays.copyOfRange(hello, tagged + CODE_LENGTH, HELLO_LENGTH))) {
            throw drop(sender, DropReason.REPLAYED, "began a connection recorded earlier (a hello of the bus's secret"
                    + " made for another connection)");
        }
        return new Link(connectionKey(macKey, Arrays.copyOfRange(hello, HELLO_TAG.length, tagged), acceptorNonce));
    }

    /** The hello of an opener with nonce {@code openerNonce} to the challenge {@code acceptorNonce}. */
    static byte[] hello(Mac mac, byte[] openerNonce, byte[] acceptorNonce) {
        byte[] tagged = concat(HELLO_TAG, openerNonce);
        mac.update(tagged);
        byte[] secret = mac.doFinal();
        mac.update(tagged);
        mac.update(acceptorNonce);
        return concat(tagged, secret, mac.doFinal());
    }

    /** {@code Kc = HMAC(K, "dtron-bus-conn-v1" nA nB)}. */
    static byte[] connectionKey(byte[] macKey, byte[] openerNonce, byte[] acceptorNonce) {
        Mac mac = newMac(macKey);
        mac.update(CONNECTION_KEY_LABEL);
        mac.update(openerNonce);
        mac.update(acceptorNonce);
        return mac.doFinal();
    }

    /** A frame this member sent to itself through its server: never (see {@link #send}); anything else is dropped. */
    @Override
    public void receive(Address sender, byte[] data, int offset, int length) {
        note(sender, DropReason.UNAUTHENTICATED, "came on no connection");
    }

    private byte[] nonce() {
        byte[] nonce = new byte[NONCE_LENGTH];
        random.nextBytes(nonce);
        return nonce;
    }

    /** Counts and logs a dropped frame; returns what ends its connection. */
    private DroppedConnection drop(Address sender, DropReason reason, String what) {
        note(sender, reason, what);
        return new DroppedConnection();
    }

    private void note(Address sender, DropReason reason, String what) {
        drops.get(reason).increment();
        String host = host(sender);
        if (NAMED.add(busName + "\n" + host + "\n" + reason)) {
            if (reason == DropReason.REPLAYED) {
                LOG.warn("Bus '{}': dropped a frame from {} that {}: someone who can read the bus's traffic sent it"
                        + " again; not logged again for host {}", busName, sender, what, host);
            } else {
                LOG.warn("Bus '{}': dropped a frame from {} that {}, as every frame without this bus's code is dropped"
                        + " (its sender lacks the bus's secret, one of the two was started with --insecure, or its"
                        + " DTRON is older than the handshake of connections); not logged again for host {}", busName,
                        sender == null ? "a connection" : sender, what, host);
            }
        }
    }

    private static String host(Address sender) {
        if (sender instanceof IpAddress ip) {
            InetAddress address = ip.getIpAddress();
            return address == null ? "" : address.getHostAddress();
        }
        return String.valueOf(sender);
    }

    private static void closeQuietly(Connection conn) {
        try {
            conn.close(false);
        } catch (IOException e) {
            // closed already
        }
    }

    static byte[] concat(byte[]... parts) {
        int length = 0;
        for (byte[] part : parts) {
            length += part.length;
        }
        byte[] all = new byte[length];
        int at = 0;
        for (byte[] part : parts) {
            System.arraycopy(part, 0, all, at, part.length);
            at += part.length;
        }
        return all;
    }

    /** The codes of one connection: its key {@code Kc} and the place of its next frame. */
    static final class Link {
        private final Mac mac;
        private final byte[] place = new byte[1 + Long.BYTES];
        private long next;

        Link(byte[] connectionKey) {
            this.mac = newMac(connectionKey);
            place[0] = TO_ACCEPTOR;
        }

        /** Writes the code of the next frame, {@code frame[0..length)}, into {@code frame[length..length+32)}. */
        void code(byte[] frame, int length) {
            start(frame, length);
            try {
                mac.doFinal(frame, length);
            } catch (ShortBufferException e) {
                throw new IllegalStateException("no room for the code", e);
            }
            next++;
        }

        /** Whether {@code frame[length..length+32)} is the code of the next frame {@code frame[0..length)}. */
        boolean check(byte[] frame, int length) {
            start(frame, length);
            byte[] expected = mac.doFinal();
            if (!MessageDigest.isEqual(expected, Arrays.copyOfRange(frame, length, length + CODE_LENGTH))) {
                return false;
            }
            next++;
            return true;
        }

        private void start(byte[] frame, int length) {
            for (int i = 0; i < Long.BYTES; i++) {
                place[1 + i] = (byte) (next >>> (8 * (Long.BYTES - 1 - i)));
            }
            mac.update(place);
            mac.update(frame, 0, length);
        }
    }

    /** A connection another member opened to this one; read by its reader thread only. */
    private static final class Accepted {
        final Connection connection;
        final byte[] nonce;
        Link link;

        Accepted(Connection connection, byte[] nonce) {
            this.connection = connection;
            this.nonce = nonce;
        }
    }

    /** A connection this member opened: its frames wait for the challenge, then go out coded, in order. */
    private final class Opened {
        final Connection connection;
        final byte[] nonce;
        private Link link;
        /** Frames with room for their codes. */
        private final ArrayDeque<byte[]> pending = new ArrayDeque<>();
        private int pendingBytes;

        Opened(Connection connection, byte[] nonce) {
            this.connection = connection;
            this.nonce = nonce;
        }

        synchronized boolean challenged() {
            return link != null;
        }

        /** The challenge came: answers it with the hello, then sends the frames that waited for it. */
        synchronized void challenge(byte[] acceptorNonce) throws Exception {
            byte[] hello = hello(macs.get(), nonce, acceptorNonce);
            link = new Link(connectionKey(macKey, nonce, acceptorNonce));
            connection.send(hello, 0, hello.length);
            for (byte[] frame = pending.poll(); frame != null; frame = pending.poll()) {
                send(frame);
            }
            pendingBytes = 0;
        }

        /** Sends a frame with its code in its last 32 bytes (or keeps it for the challenge). */
        synchronized void send(byte[] frame) throws Exception {
            if (link == null) {
                if (pendingBytes + frame.length <= PENDING_LIMIT) {
                    pending.add(frame);
                    pendingBytes += frame.length;
                }
                return;
            }
            link.code(frame, frame.length - CODE_LENGTH);
            connection.send(frame, 0, frame.length);
        }
    }

    /** A connection's read buffer: once closed, it fails its reader as a closed socket does. */
    private static final class QuietBuffer extends BufferedInputStream {
        /** JGroups' own buffer's size. */
        private static final int SIZE = 64 * 1024;

        QuietBuffer(InputStream socket) {
            super(socket, SIZE);
        }

        @Override
        public int read() throws IOException {
            try {
                return super.read();
            } catch (IOException e) {
                throw closed(e);
            }
        }

        @Override
        public int read(byte[] b, int off, int len) throws IOException {
            try {
                return super.read(b, off, len);
            } catch (IOException e) {
                throw closed(e);
            }
        }

        private IOException closed(IOException e) {
            return buf == null ? new SocketException("Socket closed") : e;
        }
    }

    /** Ends a connection quietly: JGroups closes a connection whose reader meets the end of its stream unlogged. */
    private static final class DroppedConnection extends EOFException {
        private static final long serialVersionUID = 1L;

        DroppedConnection() {
            super("frame dropped");
        }
    }
}
