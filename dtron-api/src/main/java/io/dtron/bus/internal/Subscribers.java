package io.dtron.bus.internal;

import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.function.Consumer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. A transport's handlers (per group, and of every group) and view listeners: registration, and delivery
 * that never lets a handler's exception escape into the transport's thread. Thread-safe.
 */
public final class Subscribers {
    private static final Logger LOG = LoggerFactory.getLogger(Subscribers.class);

    private final Map<String, List<Consumer<BusMessage>>> groupHandlers = new ConcurrentHashMap<>();
    private final List<Consumer<BusMessage>> allHandlers = new CopyOnWriteArrayList<>();
    private final List<Consumer<MembershipView>> viewListeners = new CopyOnWriteArrayList<>();

    /** Calls {@code handler} with each message of {@code group} until the subscription is closed. */
    public Subscription subscribe(String group, Consumer<BusMessage> handler) {
        Objects.requireNonNull(group, "group");
        Objects.requireNonNull(handler, "handler");
        groupHandlers.computeIfAbsent(group, g -> new CopyOnWriteArrayList<>()).add(handler);
        return () -> groupHandlers.computeIfPresent(group, (g, handlers) -> {
            handlers.remove(handler);
            return handlers.isEmpty() ? null : handlers;
        });
    }

    /** Calls {@code handler} with every message, of any group, until the subscription is closed. */
    public Subscription subscribeAll(Consumer<BusMessage> handler) {
        Objects.requireNonNull(handler, "handler");
        allHandlers.add(handler);
        return () -> allHandlers.remove(handler);
    }

    /** Calls {@code listener} with each new view until the subscription is closed. */
    public Subscription addViewListener(Consumer<MembershipView> listener) {
        Objects.requireNonNull(listener, "listener");
        viewListeners.add(listener);
        return () -> viewListeners.remove(listener);
    }

    /** Whether some handler takes messages of {@code group}: when none does, a message need not be decoded. */
    public boolean wants(String group) {
        return !allHandlers.isEmpty() || groupHandlers.containsKey(group);
    }

    /** Hands a message to the handlers of every group, then to those of its group; logs what a handler throws. */
    public void deliver(BusMessage message) {
        allHandlers.forEach(handler -> call(handler, message, "Bus handler"));
        groupHandlers.getOrDefault(message.group(), List.of()).forEach(handler -> call(handler, message,
                "Bus handler"));
    }

    /** Hands a new view to the view listeners; logs what a listener throws. */
    public void viewChanged(MembershipView view) {
        viewListeners.forEach(listener -> call(listener, view, "View listener"));
    }

    private static <T> void call(Consumer<T> consumer, T value, String what) {
        try {
            consumer.accept(value);
        } catch (RuntimeException e) {
            LOG.error("{} failed on {}", what, value, e);
        }
    }
}
