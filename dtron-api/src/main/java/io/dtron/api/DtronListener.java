package io.dtron.api;

import java.util.Objects;

/**
 * Receives the messages of one channel from a {@link Dtron}.
 *
 * <p>All listeners of a {@code Dtron} are called on one thread, one message at
 * a time, in the bus's total order. A listener may reply inline through
 * {@link #getDtron()}. An exception thrown by {@link #messageReceived} is logged
 * with the message and counted; the listener keeps receiving.
 *
 * <p>An input of the current run's tester is {@linkplain Dtron#ACK acknowledged}
 * when the last listener of its channel has returned (or thrown), with that
 * time as the time the input was applied, unless a listener says otherwise
 * through {@link #autoAcknowledge()}.
 */
public abstract class DtronListener {
    private final IDtronChannel channel;
    private volatile Dtron dtron;

    /**
     * Creates a listener.
     *
     * @param channel the channel to listen to; its template decides which variables messages must carry
     */
    protected DtronListener(IDtronChannel channel) {
        this.channel = Objects.requireNonNull(channel, "channel");
    }

    /** Returns the channel this listener listens to. */
    public final IDtronChannel getChannel() {
        return channel;
    }

    /**
     * Returns the {@code Dtron} this listener is added to, for replies.
     *
     * @throws IllegalStateException if the listener is not added to one
     */
    public final Dtron getDtron() {
        Dtron current = dtron;
        if (current == null) {
            throw new IllegalStateException("listener not added to a Dtron");
        }
        return current;
    }

    /** Called with every valid message of the channel. */
    public abstract void messageReceived(IDtronChannelValued message);

    /**
     * Returns whether the {@code Dtron} may acknowledge the inputs this listener receives as applied when its
     * listeners of the channel have returned; true unless overridden. A listener that applies an input later (on
     * a thread of its own) or knows better when it took effect returns false and acknowledges each input itself
     * with {@link Dtron#acknowledge(IDtronChannelValued, long)}; the input is not acknowledged automatically if
     * any listener of its channel returns false.
     */
    protected boolean autoAcknowledge() {
        return true;
    }

    /**
     * Returns whether this listener makes its member serve the channel (a receiver of its messages, in what the
     * member tells testers in the channel-serving handshake); true unless overridden. A listener that only observes
     * the channel, as a monitor's does, returns false: a tester then does not take its member for a part of the
     * system under test. Asked once, when the listener is added.
     */
    protected boolean serves() {
        return true;
    }

    /** Attaches this listener to a {@code Dtron}; false if it already is attached to another one. */
    final synchronized boolean attach(Dtron owner) {
        if (dtron != null && dtron != owner) {
            return false;
        }
        dtron = owner;
        return true;
    }

    final synchronized void detach(Dtron owner) {
        if (dtron == owner) {
            dtron = null;
        }
    }

    @Override
    public String toString() {
        return getClass().getName() + "[" + channel.getChannelName() + "]";
    }
}
