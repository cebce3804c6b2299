package io.dtron.bus.internal;

import java.io.IOException;
import java.util.Map;
import java.util.function.Consumer;

/**
 * A connected member of a publish/subscribe bus with total order.
 *
 * <p>Contract for implementations:
 * <ul>
 *   <li>Every member receives every message published on a group it
 *       subscribes to, including its own, and all members receive the
 *       messages of all senders in the same order.</li>
 *   <li>Handlers are called on the transport's receive thread, one message
 *       at a time, in that order; a handler must return quickly and must not
 *       throw (an exception is logged and the next message still delivered).</li>
 *   <li>All methods are thread-safe. After {@link #close()} publishing fails
 *       and no handler is called any more.</li>
 * </ul>
 */
public interface Transport extends AutoCloseable {

    /** Returns this member's id on the bus, unique among the current members. */
    String localMember();

    /**
     * Publishes a payload to every member subscribed to a group.
     *
     * @param group   the group (a channel name without its {@code i_}/{@code o_} prefix)
     * @param payload the bytes to deliver; not copied, so not to be changed afterwards
     * @throws IOException if the transport could not hand the message to the bus
     * @throws IllegalStateException if the transport is closed
     */
    void publish(String group, byte[] payload) throws IOException;

    /**
     * Calls a handler for every message on one group, from now on.
     *
     * @return the subscription, whose {@link Subscription#close()} stops the calls
     */
    Subscription subscribe(String group, Consumer<BusMessage> handler);

    /**
     * Calls a handler for every message on every group, from now on.
     *
     * @return the subscription, whose {@link Subscription#close()} stops the calls
     */
    Subscription subscribeAll(Consumer<BusMessage> handler);

    /** Returns the current membership view. */
    MembershipView view();

    /**
     * Calls a listener with every new membership view, from now on, on the
     * transport's thread.
     *
     * @return the subscription, whose {@link Subscription#close()} stops the calls
     */
    Subscription addViewListener(Consumer<MembershipView> listener);

    /**
     * Returns how many received messages the transport dropped before any handler or view saw them, by reason
     * (messages without a valid code of the bus's secret); reasons left out count 0.
     */
    default Map<DropReason, Long> drops() {
        return Map.of();
    }

    /** Leaves the bus and releases its resources; closing twice does nothing. */
    @Override
    void close();
}
