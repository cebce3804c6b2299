package io.dtron.api.internal;

import io.dtron.api.Dtron;
import io.dtron.api.DtronException;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.MemberDelay;
import io.dtron.api.ServedChannels;
import java.time.Duration;
import java.util.Collection;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.function.Consumer;
import java.util.function.Function;

/**
 * Not API. What only a tester (or another role that owns a run on the bus: a monitor, a controller) does with its
 * bus member, beside what every adapter does through {@link Dtron}: stamp its run id, probe the members, learn who
 * else tests on the bus, the delays of the members' messages and what they serve. {@link #of} gives a member's.
 */
public interface TesterSide {
    /** Returns the tester side of a bus member. */
    static TesterSide of(Dtron dtron) {
        return Access.get().apply(Objects.requireNonNull(dtron, "dtron"));
    }

    /**
     * Sets the run id this member stamps on the messages it sends from now on; "" for none. A member that sets
     * none stamps the id of the current run, as the run's {@link Dtron#RUN_START} carried it, until the run stops. A
     * tester sets it before publishing {@code RUN_START}.
     */
    void setRunId(String id);

    /**
     * Publishes a run's start ({@link Dtron#RUN_START}) with time 0 as its event time and the end of the run the
     * tester announces ({@link IDtronChannelValued#getEndTimeNanos()}; 0 for none), both on this
     * member's wall clock in nanoseconds since the epoch.
     *
     * @return the start as published
     * @throws IllegalArgumentException if the message is no run start, or time 0 is not positive
     * @throws DtronException           if the bus did not take it
     */
    IDtronChannelValued sendRunStart(IDtronChannelValued start, long zeroEpochNanos, long endEpochNanos);

    /**
     * Publishes an input ahead of its time, with the time it is due on this member's wall clock in nanoseconds since
     * the epoch ({@link IDtronChannelValued#getDueTimeNanos()}): a member that {@linkplain #holdsInputs holds
     * inputs} hands it to its listeners then, not before.
     *
     * @return the input as published
     * @throws IllegalArgumentException if the due time is not positive, or the message is none of a model channel
     * @throws DtronException           if the bus did not take it
     */
    IDtronChannelValued sendAhead(IDtronChannelValued input, long dueEpochNanos);

    /**
     * Whether {@code member} said in the channel-serving handshake that it holds an input sent ahead until it is due
     * (as every member of this API does; other languages' clients apply every input on arrival).
     */
    boolean holdsInputs(String member);

    /**
     * Asks members whether they are there: pings the bus and waits until each of {@code members} answered, or the
     * timeout passed. A member answers this ping (marked {@code probe}) from its own thread whoever sent it, a tester
     * or a live monitor, as long as its process runs and reaches the bus; a member that was killed, stopped or cut
     * off does not, nor does one of DTRON before the mark, but for its tester's ping. Since every member's messages
     * arrive in the order it sent them, an answer also means that the messages it sent before have arrived: when this
     * returns, they have been delivered to this member's listeners.
     *
     * @return the members of {@code members} that answered
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    Set<String> probe(Collection<String> members, Duration timeout) throws InterruptedException;

    /**
     * Probes members as {@link #probe} does, through the path of an input, for a tester warming its adapters up
     * before a run: a member built on DTRON's API answers on the thread of its listeners, in order with the messages
     * they hear, and with the {@linkplain Dtron#ACK acknowledgement} it publishes when it applied an input, but calls
     * none of its listeners (the system under test does not hear of it). So a fresh process runs that path for the
     * first time before the run, and the round trip is that of an input. A member that does not know this probe (an
     * older API, another language's client) answers it as any ping, which counts as well. Not for telling whether a
     * member is there: a listener that is busy holds the answer up.
     *
     * @return the members of {@code members} that answered
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    Set<String> probeAsInput(Collection<String> members, Duration timeout) throws InterruptedException;

    /**
     * Waits until the thread of the {@link io.dtron.api.DtronListener}s has handled what this member had received when
     * called: the messages, the members' announcements of what they serve (the {@linkplain
     * #addServedChannelsListener served-channels listeners}) and the news of who joined or left. So what the
     * listeners know then is at least what {@link #getMembersServedChannels()} and {@link Dtron#getMembers()} said
     * before the call. Returns at once on that thread, and once the member is closed.
     *
     * @return whether the listeners' thread has handled it, within the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    boolean awaitListeners(Duration timeout) throws InterruptedException;

    /**
     * Returns the other members that announced themselves as a tester (connected with the {@linkplain
     * io.dtron.api.DtronOptions.Builder#tester tester} option, or by publishing {@link Dtron#RUN_START}), by a
     * greeting or in the handshake, and are on the bus now. A tester that finds another one here shares its bus with
     * another run: its adapters would follow both.
     */
    Set<String> getOtherTesters();

    /**
     * Returns whether another member said it is a tester (by a greeting, in the handshake or by starting a run)
     * while it was on the bus; still true after it left. For a tester deciding whether a member that has just left
     * stood for part of the system under test.
     */
    boolean wasTester(String member);

    /**
     * The end of a run as its tester announced it (in its {@link Dtron#RUN_START}) in its latest answer to this
     * member's clock ping: the tester's pongs during a run carry it, so that a member that joined during the run,
     * and so saw no start, learns it within a ping period (a second). Of the run {@code runId}; {@code endNanos} on
     * the tester's wall clock in nanoseconds since the epoch, 0 when the run announced none or no run was going.
     */
    record AnnouncedEnd(String runId, long endNanos) {
    }

    /** Returns the end of the run the tester's latest pong to this member announced ({@link AnnouncedEnd}). */
    AnnouncedEnd announcedEnd();

    /**
     * Returns how long the messages of each other member took to arrive, on the tester's clock: publish time plus
     * the sender's clock offset estimate, to receive time plus this member's, over every message that carried an
     * estimate or came from the tester (members ping the tester once a second, and {@link #probe} asks them all).
     * By member id in id order; members that left are kept. Empty while this member has no clock offset estimate.
     */
    Map<String, MemberDelay> getDelaysFromMembers();

    /**
     * Returns what the other members on the bus said they serve, by member id in id order (testers say that they
     * are); members that said nothing (adapters built against an API without the handshake) are left out; an
     * immutable snapshot, cheap to take on every message. A tester waits until its model's channels are all served
     * before it starts a run.
     */
    Map<String, ServedChannels> getMembersServedChannels();

    /**
     * Adds a listener that is told what the other members serve (as {@link #getMembersServedChannels()} returns
     * it) whenever that changes: a member said what it serves, or one that had said it left. It is called on the
     * thread of the {@link io.dtron.api.DtronListener}s, in order with the messages: a member's announcement comes
     * before the messages it sent after it, and its messages before the news that it left. For a tester, which
     * judges who sends on its channels; a listener added twice is called once.
     */
    void addServedChannelsListener(Consumer<Map<String, ServedChannels>> listener);

    /** Removes a listener of {@link #addServedChannelsListener}; removing an unknown one does nothing. */
    void removeServedChannelsListener(Consumer<Map<String, ServedChannels>> listener);

    /**
     * Says whether this member is a tester that takes part in the next run another tester starts on this bus
     * ({@code dtron run --join}): the starting tester waits for the testers that said so. Told in the handshake.
     */
    void setJoiningRun(boolean joining);

    /** Not API. How {@link Dtron} hands out its members' tester sides, once. */
    final class Access {
        private static volatile Function<Dtron, TesterSide> access;

        private Access() {
        }

        /**
         * Called once, by {@link Dtron} as its class is initialised.
         *
         * @throws IllegalStateException when called again
         */
        public static synchronized void grant(Function<Dtron, TesterSide> testerSide) {
            if (access != null) {
                throw new IllegalStateException("the tester side is granted once, by Dtron");
            }
            access = testerSide;
        }

        private static Function<Dtron, TesterSide> get() {
            Function<Dtron, TesterSide> granted = access;
            if (granted == null) {
                throw new IllegalStateException("Dtron has not been initialised");
            }
            return granted;
        }
    }
}
