package io.dtron.api;

import java.util.Objects;

/**
 * Receives the messages of one channel from a {@link Dtron}.
 *
 * <p>All listeners of a {@code Dtron} are called one message at a time, in the
 * bus's total order, on the {@code Dtron}'s listeners' thread; a listener that
 * says so ({@link #onReceivingThread()}) may instead be called on the bus
 * transport's receiving thread when nothing else is pending. A listener may
 * reply inline through {@link #getDtron()} (one called on the receiving thread
 * may not). An exception thrown by {@link #messageReceived} is logged
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

    /**
     * Returns whether this listener may be called on the bus transport's receiving thread (on an in-JVM bus, which
     * hands messages over in memory, that may be the sending member's thread); false unless overridden. Asked once,
     * when the listener is added. A message whose channel's listeners all say so is handed to them on the thread
     * that received it when no message is queued for the listeners and none is being delivered, which spares a
     * hand-off between threads (on a virtual machine whose idle CPUs sleep, 1 to 11 ms to wake the listeners'
     * thread); otherwise it queues as any other. Either way listeners are called one message at a time, in the bus's
     * order: a message received meanwhile waits for this one's listeners.
     *
     * <p>A listener that returns true promises that {@link #messageReceived} returns quickly and waits for nothing
     * the bus delivers: it must not send on the bus ({@link Dtron#send} throws there), close the {@code Dtron}, wait
     * for a message or a membership change, nor wait for a lock or any other thread that may itself be sending on
     * the bus. On JGroups a member's first sends after it joined (and after a new coordinator took over) wait until
     * the bus hands them back, on the very thread such a listener holds: waiting for that thread's send, the listener
     * and the sender would wait for each other for good. Scheduling work on another thread ({@link
     * RunClock#scheduleAt}, an executor) is fine, and so is {@link Dtron#acknowledge(IDtronChannelValued, long)},
     * which then publishes when the listener has returned. The automatic acknowledgement of an input is published
     * then too, with the time the listener returned.
     */
    protected boolean onReceivingThread() {
        return false;
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
