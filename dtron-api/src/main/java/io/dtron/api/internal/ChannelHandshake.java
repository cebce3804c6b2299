package io.dtron.api.internal;

import io.dtron.api.ServedChannels;
import java.util.Collection;
import java.util.Collections;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeMap;
import java.util.TreeSet;
import java.util.concurrent.Executor;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.function.Consumer;

/**
 * Not API. One member's side of the channel-serving handshake: the channels it serves (receives, by listeners, and
 * sends), announced on {@link #SERVE} whenever they change and whenever a tester's hello arrives; and the last
 * announcement of every other member on the bus. A tester announces its channels too, saying that it is a tester:
 * it serves none of them, it tests them. A channel this member starts sending on is announced before {@link
 * #sending} returns, so that on the bus the announcement comes before the first message on it: a tester takes a
 * message from a member that did not say it sends on that channel for another system's (see the channel owners on
 * the tester's side).
 * Thread-safe.
 */
public final class ChannelHandshake {
    /** The channel of the announcements. */
    public static final String SERVE = "dtron_serve";

    private final String me;
    private final Executor executor;
    private final Consumer<ServedChannels> publisher;
    private final Runnable othersChanged;
    private final Set<String> receives = new TreeSet<>();
    private final Set<String> sends = new TreeSet<>();
    /** The other members' last announcements, by member id: an immutable snapshot, replaced on every change. */
    private volatile Map<String, ServedChannels> others = Map.of();
    private final Object othersLock = new Object();
    private final AtomicBoolean queued = new AtomicBoolean();
    /** Held while an announcement is taken and published: announcements go out in the order they were taken. */
    private final Object publishing = new Object();
    private boolean joinsRun;
    private boolean tester;

    /**
     * Creates a member's side.
     *
     * @param me            this member's id
     * @param executor      where announcements are published, one at a time
     * @param publisher     publishes this member's channels on {@link #SERVE}; must not throw
     * @param othersChanged called (without locks held) when another member's announcement arrived or it left
     * @param tester        whether this member is a tester from the start
     */
    public ChannelHandshake(String me, Executor executor, Consumer<ServedChannels> publisher,
            Runnable othersChanged, boolean tester) {
        this.me = me;
        this.tester = tester;
        this.executor = executor;
        this.publisher = publisher;
        this.othersChanged = othersChanged;
    }

    /** This member listens to a channel ({@code on}) or stopped listening to it; announced when that changes. */
    public void receiving(String channel, boolean on) {
        boolean changed;
        synchronized (this) {
            changed = on ? receives.add(channel) : receives.remove(channel);
        }
        if (changed) {
            announce();
        }
    }

    /**
     * This member sends on these channels; when that adds one, announced before this returns (on the caller's thread),
     * so that a message the caller publishes next comes after the announcement on the bus.
     */
    public void sending(Collection<String> channels) {
        boolean changed;
        synchronized (this) {
            changed = sends.addAll(channels);
        }
        if (changed) {
            synchronized (publishing) {
                publisher.accept(own());
            }
        }
    }

    /** This member is a tester that joins the next run another tester starts ({@code on}), or no longer is. */
    public void joiningRun(boolean on) {
        boolean changed;
        synchronized (this) {
            changed = joinsRun != on;
            joinsRun = on;
        }
        if (changed) {
            announce();
        }
    }

    /** This member became a tester (it started a run); announced if it was none. */
    public void testing() {
        boolean changed;
        synchronized (this) {
            changed = !tester;
            tester = true;
        }
        if (changed) {
            announce();
        }
    }

    /** Returns the channels this member serves. */
    public synchronized ServedChannels own() {
        return new ServedChannels(me, receives, sends, joinsRun, tester);
    }

    /** A tester greeted the bus (this member too, if it is one): this member tells it what it serves. */
    public void helloReceived() {
        announce();
    }

    /** Another member said what it serves. */
    public void servedReceived(ServedChannels served) {
        if (served.member().equals(me)) {
            return;
        }
        boolean changed;
        synchronized (othersLock) {
            changed = !served.equals(others.get(served.member()));
            if (changed) {
                Map<String, ServedChannels> next = new TreeMap<>(others);
                next.put(served.member(), served);
                others = Collections.unmodifiableMap(next);
            }
        }
        if (changed) {
            othersChanged.run();
        }
    }

    /** Forgets the members that left. */
    public void viewChanged(List<String> members) {
        boolean changed;
        synchronized (othersLock) {
            Map<String, ServedChannels> next = new TreeMap<>(others);
            changed = next.keySet().retainAll(members);
            if (changed) {
                others = Collections.unmodifiableMap(next);
            }
        }
        if (changed) {
            othersChanged.run();
        }
    }

    /**
     * Returns what each other member on the bus said it serves, by member id in id order (those that said nothing
     * left out): an immutable snapshot, cheap to take (the handshake's messages replace it; reads do not copy).
     */
    public Map<String, ServedChannels> others() {
        return others;
    }

    /** Returns whether another member said it is a tester joining the next run another one starts. */
    public boolean joinsRun(String member) {
        ServedChannels served = others.get(member);
        return served != null && served.joinsRun();
    }

    /** Queues one announcement of this member's current channels, unless one is queued already. */
    private void announce() {
        if (!queued.compareAndSet(false, true)) {
            return;
        }
        executor.execute(() -> {
            queued.set(false);
            synchronized (publishing) {
                publisher.accept(own());
            }
        });
    }
}
