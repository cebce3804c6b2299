package io.dtron.bridge;

import java.time.Duration;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.OptionalLong;
import java.util.concurrent.TimeUnit;

/**
 * The steps of a tester's run on the bus before its time 0, in their order: whether a tester of another run is there
 * first ({@link #otherRunFirst}); then ({@link #prepare}) waiting for the adapters (every channel served, or a number
 * of members), refusing outputs with two owners, the other testers of a run of several (this tester starts it, or
 * joins one), the probes before the run while the engine warms up, the delays measured and the reorder window they
 * give, and time 0 (announced to the testers that joined, or taken from the tester that starts the run). A command
 * says what happens through {@link Steps} and why a run cannot start from the {@link Refusal}; it starts the engine
 * with the {@link BusRun}'s {@link BusBridge} after it. A controller's run goes through the same steps but the
 * several-tester ones ({@link #prepareForControl}).
 */
public final class BusRunSequence {
    /** How long adapters that just joined get to add their listeners before the run starts. */
    static final Duration SETTLE = Duration.ofMillis(250);
    /** How long the wait for the channels to be served goes before it says what is still missing. */
    private static final Duration MISSING_EVERY = Duration.ofSeconds(5);

    private final BusRun run;

    /** The sequence of {@code run}. */
    public BusRunSequence(BusRun run) {
        this.run = Objects.requireNonNull(run, "run");
    }

    /**
     * How a run waits and starts.
     *
     * @param timeout         how long to wait for the adapters, for the other testers, and for the run's start
     * @param adapters        -1: wait until every channel of the model is served; else how many adapter members to
     *                        wait for (0: none)
     * @param testers         how many testers the run has, this one included, when this tester starts it (1: alone)
     * @param fixedWindow     the reorder window in microseconds; empty: automatic, from the delays measured
     * @param timeUnitMicros  the run's time unit, which a run of several testers announces
     * @param engineWarmUp    what warms the engine up while the adapters are probed, on a thread of its own; null
     *                        when nothing does (the probes then stop once steady)
     */
    public record Settings(Duration timeout, int adapters, int testers, OptionalLong fixedWindow, long timeUnitMicros,
            Runnable engineWarmUp) {
    }

    /** What the sequence tells as it goes; every step does nothing by default. */
    public interface Steps {
        /** It waits for the channels the adapters on the bus do not serve yet. */
        default void waitingForChannels(Duration wait, List<String> missing) {
        }

        /** What is still missing changed while it waited. */
        default void stillMissing(List<String> missing) {
        }

        /** Every channel of the model is served (it had to wait or not). */
        default void channelsServed() {
        }

        /** It waits for a number of adapter members. */
        default void waitingForAdapters(Duration wait, int wanted) {
        }

        /** The adapter members it waited for are there: the members now. */
        default void adaptersJoined(List<String> members) {
        }

        /** A joining tester is ready, and waits for the tester that starts the run. */
        default void readyToJoin(Duration wait) {
        }

        /** It waits for the other testers of a run of several. */
        default void waitingForTesters(Duration wait, int others) {
        }

        /** The other testers of a run of several are there. */
        default void testersJoined(List<String> testers) {
        }

        /** The probes before the run are done (a joining tester does not probe). */
        default void probed(BusRun.Probing probing, boolean engineWarmedUp) {
        }

        /** The engine's warm-up, if any, is over, after the probes. */
        default void warmedUp() {
        }

        /** The delays measured before the run, and the reorder window the run starts with. */
        default void delays(BusRun.Delays delays, long windowMicros, boolean automatic) {
        }
    }

    /** Why a run does not start. */
    public enum Reason {
        /** A tester of another run joined the bus first ({@link Refusal#names}: the testers). */
        OTHER_RUN,
        /** Within the wait, no adapter served some channels ({@link Refusal#names}: "input X", "output Y"). */
        CHANNELS_UNSERVED,
        /** Within the wait, too few adapter members joined ({@link Refusal#count} of {@link Refusal#wanted}). */
        ADAPTERS_MISSING,
        /** Two members own one output, or have one id ({@link Refusal#names}: the one-line reason). */
        OWNERS,
        /** A joining tester found no tester that starts a run within the wait. */
        NO_STARTING_TESTER,
        /** Too few other testers joined the run within the wait ({@link Refusal#count} of {@link Refusal#wanted}). */
        TESTERS_MISSING,
        /** A joining tester saw no run start within the wait. */
        NO_RUN_STARTED,
        /** The thread was interrupted ({@link Refusal#names}: while doing what). */
        INTERRUPTED
    }

    /**
     * Why a run does not start, with what names it.
     *
     * @param reason what stops it
     * @param names  the members, channels or words the reason names
     * @param count  how many came, where the reason counts (0 where it counts none)
     * @param wanted how many it waited for, where the reason counts (0 where it counts none)
     */
    public record Refusal(Reason reason, List<String> names, int count, int wanted) {
        /** The refusal with {@code names}. */
        static Refusal of(Reason reason, List<String> names) {
            return new Refusal(reason, List.copyOf(names), 0, 0);
        }

        /** The refusal with how many came of how many wanted. */
        static Refusal counted(Reason reason, int count, int wanted) {
            return new Refusal(reason, List.of(), count, wanted);
        }
    }

    /** Returns the run. */
    public BusRun run() {
        return run;
    }

    /**
     * Before the adapters of this process join: the testers of other runs that joined the bus first ({@link
     * BusRun#testersThatJoinedFirst}), whose adapters would serve both runs. A joining tester does not ask.
     */
    public Optional<Refusal> otherRunFirst() {
        if (run.isJoining()) {
            return Optional.empty();
        }
        try {
            List<String> others = run.testersThatJoinedFirst();
            return others.isEmpty() ? Optional.empty() : Optional.of(Refusal.of(Reason.OTHER_RUN, others));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return Optional.of(Refusal.of(Reason.INTERRUPTED, List.of("joining the bus")));
        }
    }

    /**
     * Everything between the adapters' joining and time 0 (see the class): when it returns empty the run starts with
     * the reorder window {@link BusRun#reorderWindowMicros()}.
     */
    public Optional<Refusal> prepare(Settings settings, Steps steps) {
        Optional<Refusal> refused;
        try {
            refused = settings.adapters() < 0 ? awaitChannels(settings.timeout(), steps)
                    : awaitAdapters(settings.adapters(), settings.timeout(), steps);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return Optional.of(Refusal.of(Reason.INTERRUPTED, List.of("waiting for the adapters")));
        }
        if (refused.isEmpty()) {
            refused = owners();
        }
        if (refused.isPresent()) {
            return refused;
        }
        run.expectAdapters();
        try {
            return startOfRun(settings, steps).or(this::owners);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return Optional.of(Refusal.of(Reason.INTERRUPTED, List.of("preparing the run")));
        }
    }

    /** The testers of a run of several, the probes, the delays and the window, and time 0. */
    private Optional<Refusal> startOfRun(Settings settings, Steps steps) throws InterruptedException {
        boolean joining = run.isJoining();
        boolean several = !joining && settings.testers() > 1;
        if (joining) {
            if (!run.readyToJoin(settings.timeout())) {
                return Optional.of(Refusal.of(Reason.NO_STARTING_TESTER, List.of()));
            }
            steps.readyToJoin(settings.timeout());
        } else if (several) {
            int others = settings.testers() - 1;
            steps.waitingForTesters(settings.timeout(), others);
            if (!run.awaitJoiningTesters(others, settings.timeout())) {
                return Optional.of(Refusal.counted(Reason.TESTERS_MISSING, run.joiningTesters().size(), others));
            }
            steps.testersJoined(run.joiningTesters());
        }
        warmUp(settings.engineWarmUp(), steps);
        BusRun.Delays delays = run.measuredDelays();
        long window = run.reorderWindow(delays, settings.fixedWindow());
        steps.delays(delays, window, run.reorderWindowAutomatic());
        // a run of several testers: every engine counts from the time 0 its start names
        if (joining) {
            if (run.awaitRun(settings.timeout()) < 0) {
                return Optional.of(Refusal.of(Reason.NO_RUN_STARTED, List.of()));
            }
        } else if (several) {
            run.announceRun(settings.timeUnitMicros());
        }
        return Optional.empty();
    }

    /**
     * Probes the adapters until their round trips are steady (a joining tester does not: it measures what passes by)
     * while the engine warms up on a thread of its own.
     */
    private void warmUp(Runnable engineWarmUp, Steps steps) throws InterruptedException {
        boolean warm = engineWarmUp != null;
        Thread warming = new Thread(warm ? engineWarmUp : () -> { }, "dtron-lateness");
        warming.setDaemon(true);
        if (warm) {
            warming.start();
        }
        if (!run.isJoining()) {
            steps.probed(run.warmUp(warm), warm);
        }
        if (warm) {
            warming.join();
            steps.warmedUp();
        }
    }

    /**
     * Before time 0 of a run whose engine side is a controller ({@code dtron control --bus}): the choreography a
     * tester's run goes through, without its several-tester parts. Waits, {@code timeout} at most, until no tester of
     * another run that joined the bus first is there (its adapters would serve both), and until the plant's adapters
     * serve every channel of the model ({@link BusRun#unservedChannels()}); refuses outputs with two owners ({@link
     * BusRun#ownersConflict()}); remembers the adapters ({@link BusRun#expectAdapters()}); and probes them until their
     * round trips are steady ({@link BusRun#warmUp}), which sets how long commands take to reach them ({@link
     * BusRun#inputDelayMicros}). Then {@link BusRun#start} starts the run.
     *
     * @return empty when the run can start, else why not, in one line
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public Optional<String> prepareForControl(Duration timeout) throws InterruptedException {
        List<String> first = run.testersThatJoinedFirst();
        if (!first.isEmpty()) {
            return Optional.of("tester " + String.join(", ", first) + " is on the bus with a run in progress, and its"
                    + " adapters would serve both runs");
        }
        if (!run.awaitChannelsServed(timeout)) {
            return Optional.of("within " + timeout.toSeconds() + " s no member on the bus served "
                    + String.join(", ", run.unservedChannels()) + " (members: " + run.members() + ")");
        }
        Optional<String> conflict = run.ownersConflict();
        if (conflict.isPresent()) {
            return conflict;
        }
        run.expectAdapters();
        run.warmUp(false);
        return Optional.empty();
    }

    /** Waits until every channel of the model is served, saying what is missing now and then. */
    private Optional<Refusal> awaitChannels(Duration wait, Steps steps) throws InterruptedException {
        long deadline = System.nanoTime() + wait.toNanos();
        List<String> missing = run.unservedChannels();
        if (!missing.isEmpty()) {
            steps.waitingForChannels(wait, missing);
        }
        while (!missing.isEmpty()) {
            long left = deadline - System.nanoTime();
            if (left <= 0) {
                return Optional.of(Refusal.of(Reason.CHANNELS_UNSERVED, missing));
            }
            run.awaitChannelsServed(Duration.ofNanos(Math.min(left, MISSING_EVERY.toNanos())));
            List<String> now = run.unservedChannels();
            if (!now.isEmpty() && !now.equals(missing)) {
                steps.stillMissing(now);
            }
            missing = now;
        }
        steps.channelsServed();
        return Optional.empty();
    }

    /** Waits until {@code wanted} adapter members are on the bus (see {@link #awaitAdapters(int, Duration)}). */
    private Optional<Refusal> awaitAdapters(int wanted, Duration wait, Steps steps) throws InterruptedException {
        if (wanted == 0) {
            return Optional.empty();
        }
        steps.waitingForAdapters(wait, wanted);
        if (!awaitAdapters(wanted, wait)) {
            return Optional.of(Refusal.counted(Reason.ADAPTERS_MISSING, run.members().size() - 1, wanted));
        }
        steps.adaptersJoined(run.members());
        return Optional.empty();
    }

    /**
     * Waits until {@code count} members other than the tester and other testers are on the bus ({@link
     * BusRun#awaitAdapters}), then a short while for the last ones to add their listeners.
     *
     * @return whether they came before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean awaitAdapters(int count, Duration timeout) throws InterruptedException {
        if (!run.awaitAdapters(count, timeout)) {
            return false;
        }
        TimeUnit.MILLISECONDS.sleep(SETTLE.toMillis());
        return true;
    }

    /** The run refuses to start while the owners of the model's outputs are ambiguous (see {@link BusRun}). */
    private Optional<Refusal> owners() {
        return run.ownersConflict().map(reason -> Refusal.of(Reason.OWNERS, List.of(reason)));
    }
}
