package io.dtron.bus.internal;

import io.dtron.bus.BusMessage;
import io.dtron.bus.MembershipView;
import io.dtron.bus.Subscription;
import io.dtron.bus.Transport;
import java.io.IOException;
import java.util.List;
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
     * Joins the cluster described by the settings.
     *
     * @throws Exception whatever JGroups throws when the stack cannot start or
     *                   the cluster refuses this member ({@link SecurityException}
     *                   when authentication fails)
     */
    public static JGroupsTransport connect(JGroupsSettings settings) throws Exception {
        JChannel channel = new JChannel(JGroupsStack.build(settings));
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
