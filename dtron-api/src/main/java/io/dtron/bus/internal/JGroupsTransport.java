package io.dtron.bus.internal;

import java.io.IOException;
import java.net.BindException;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.function.Consumer;
import org.jgroups.Address;
import org.jgroups.BytesMessage;
import org.jgroups.JChannel;
import org.jgroups.Message;
import org.jgroups.Receiver;
import org.jgroups.View;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. The default {@link Transport}: one JGroups channel per member, with
 * the stack of {@link JGroupsStack}. Every bus group travels in the one JGroups
 * cluster; each JGroups message carries one {@link Frames frame} (group name
 * and payload), and receivers pick the groups they subscribe to.
 */
public final class JGroupsTransport implements Transport, Receiver {
    private static final Logger LOG = LoggerFactory.getLogger(JGroupsTransport.class);

    private final JChannel channel;
    private final Subscribers subscribers = new Subscribers();
    private volatile MembershipView view;
    private volatile boolean closed;

    private JGroupsTransport(JChannel channel, String memberName) {
        this.channel = channel;
        this.view = new MembershipView(0, List.of(memberName));
    }

    /**
     * Joins the cluster described by the settings. Over TCP the member takes the first free bus port (on the bind
     * address); a port another process takes between the check and the bind moves it on to the next.
     *
     * @throws BindAddressException when nothing can listen on the bind address
     * @throws PortsInUseException  when no bus port is free
     * @throws Exception           whatever JGroups throws when the stack cannot start
     */
    public static JGroupsTransport connect(JGroupsSettings settings) throws Exception {
        if (settings.inJvm()) {
            return join(settings, 0);
        }
        try {
            bind(settings.bindAddress(), 0);
        } catch (IOException e) {
            throw new BindAddressException(settings.bindAddress(), e);
        }
        List<Integer> inUse = new ArrayList<>();
        for (int port = settings.port(); port < settings.port() + settings.busPorts(); port++) {
            if (taken(settings.bindAddress(), port)) {
                inUse.add(port);
                continue;
            }
            try {
                return join(settings, port);
            } catch (Exception e) {
                if (!taken(settings.bindAddress(), port) && !failedToBind(e)) {
                    throw e;
                }
                LOG.debug("Port {} taken while joining ({}); trying the next", port, e.toString());
                inUse.add(port);
            }
        }
        throw new PortsInUseException(settings, inUse);
    }

    /** Returns whether the port cannot be listened on at the address now. */
    private static boolean taken(InetAddress address, int port) {
        try {
            bind(address, port);
            return false;
        } catch (IOException e) {
            return true;
        }
    }

    /**
     * Binds a TCP socket to the address and port, and closes it: a socket that never listens (no one can connect
     * to it, and it shows in no list of listening sockets), which a port another socket listens on refuses, and a
     * port in TIME_WAIT does not.
     */
    private static void bind(InetAddress address, int port) throws IOException {
        try (Socket probe = new Socket()) {
            probe.setReuseAddress(true);
            probe.bind(new InetSocketAddress(address, port));
        }
    }

    /**
     * Whether joining failed for a port in use (a port in TIME_WAIT may refuse JGroups' bind yet let the check above
     * bind it).
     */
    private static boolean failedToBind(Throwable e) {
        for (Throwable t = e; t != null; t = t.getCause()) {
            if (t instanceof BindException) {
                return true;
            }
        }
        return false;
    }

    private static JGroupsTransport join(JGroupsSettings settings, int busPort) throws Exception {
        JChannel channel = new JChannel(JGroupsStack.build(settings, busPort));
        JGroupsTransport transport = new JGroupsTransport(channel, settings.memberName());
        try {
            channel.name(settings.memberName());
            channel.setReceiver(transport);
            channel.connect(settings.clusterName());
        } catch (Exception | Error e) {
            channel.close();
            throw e;
        }
        LOG.debug("Joined {} as {}: {}", settings, settings.memberName(), transport.view);
        return transport;
    }

    /**
     * Returns how many frames this member dropped (each ending its connection) for a missing or wrong code or length
     * (see {@link GuardedTcp}); 0 in-JVM.
     */
    public long rejectedFrames() {
        GuardedTcp tcp = channel.getProtocolStack().findProtocol(GuardedTcp.class);
        return tcp == null ? 0 : tcp.rejectedFrames();
    }

    /** The frames this member dropped, by reason (see {@link GuardedTcp}); none in-JVM. */
    @Override
    public Map<DropReason, Long> drops() {
        GuardedTcp tcp = channel.getProtocolStack().findProtocol(GuardedTcp.class);
        return tcp == null ? Map.of() : tcp.drops();
    }

    @Override
    public String localMember() {
        return channel.getName();
    }

    @Override
    public void publish(String group, byte[] payload) throws IOException {
        Objects.requireNonNull(group, "group");
        Objects.requireNonNull(payload, "payload");
        if (closed) {
            throw new IllegalStateException("transport closed");
        }
        try {
            channel.send(new BytesMessage(null, Frames.encode(group, payload)));
        } catch (IOException | RuntimeException e) {
            throw e;
        } catch (Exception e) {
            throw new IOException("cannot publish on group " + group, e);
        }
    }

    @Override
    public Subscription subscribe(String group, Consumer<BusMessage> handler) {
        return subscribers.subscribe(group, handler);
    }

    @Override
    public Subscription subscribeAll(Consumer<BusMessage> handler) {
        return subscribers.subscribeAll(handler);
    }

    @Override
    public MembershipView view() {
        return view;
    }

    @Override
    public Subscription addViewListener(Consumer<MembershipView> listener) {
        return subscribers.addViewListener(listener);
    }

    @Override
    public void close() {
        if (closed) {
            return;
        }
        closed = true;
        channel.close();
    }

    // JGroups callbacks: never let an exception escape into the JGroups thread.

    @Override
    public void receive(Message msg) {
        long receivedAt = EpochClock.nowNanos();
        if (closed) {
            return;
        }
        Address src = msg.getSrc();
        String sender = src == null ? "" : src.toString();
        Frames.Frame frame;
        try {
            frame = Frames.decode(msg.getArray(), msg.getOffset(), msg.getLength());
        } catch (RuntimeException e) {
            LOG.warn("Dropped a message from {} that is no DTRON frame: {}", sender, e.getMessage());
            return;
        }
        if (subscribers.wants(frame.group())) {
            subscribers.deliver(new BusMessage(frame.group(), frame.payload(), sender, receivedAt));
        }
    }

    @Override
    public void viewAccepted(View newView) {
        MembershipView previous = view;
        MembershipView next = new MembershipView(newView.getViewId().getId(),
                newView.getMembers().stream().map(Address::toString).toList());
        view = next;
        LOG.debug("{}: view {} (joined {}, left {})", channel.getName(), next, next.joinedSince(previous),
                next.leftSince(previous));
        subscribers.viewChanged(next);
    }
}
