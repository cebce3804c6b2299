package io.dtron.bridge.internal;

import io.dtron.api.Dtron;
import io.dtron.api.DtronException;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.ServedChannels;
import io.dtron.api.internal.TesterSide;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.TreeMap;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. The testers of a run of several ({@code dtron run --testers N} and {@code --join}): which testers are
 * ready to join the next run, which joined this one, the tester that started the run a joining tester joined, the
 * start it waits for, and the verdicts the testers tell one another at the end. A run of one tester has none.
 */
public final class RunTesters {
    private static final Logger LOG = LoggerFactory.getLogger(RunTesters.class);

    private final Dtron dtron;
    private final TesterSide tester;
    /** Whether this tester takes part in a run another tester starts. */
    private final boolean joining;
    /** The testers of a run of several that told their verdicts, with the verdicts' exit codes. */
    private final Map<String, Integer> verdicts = new ConcurrentHashMap<>();
    /** The testers that joined this run (it started it), as the run started. */
    private volatile Set<String> joiners = Set.of();
    /** For a joining tester, the tester that started the run it joined (null otherwise). */
    private volatile String leader;
    /** On a joining tester: the run start it waits for or joined. */
    private final BlockingQueue<IDtronChannelValued> starts = new LinkedBlockingQueue<>();

    /** The testers of the runs of {@code dtron}'s tester, which joins another's runs when {@code joining}. */
    public RunTesters(Dtron dtron, TesterSide tester, boolean joining) {
        this.dtron = dtron;
        this.tester = tester;
        this.joining = joining;
    }

    /** Whether this tester joins a run another tester starts. */
    public boolean joining() {
        return joining;
    }

    /** A run start came from the bus: a joining tester keeps another tester's, for {@link #awaitStart}. */
    public void started(IDtronChannelValued start) {
        if (joining && !start.getSender().equals(dtron.getMemberId())) {
            starts.add(start);
        }
    }

    /**
     * A joining tester tells the bus it is ready, once it knows its clock's offset to the tester that starts the
     * run.
     *
     * @return whether it was ready before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean readyToJoin(Duration timeout) throws InterruptedException {
        long deadline = System.nanoTime() + timeout.toNanos();
        while (!dtron.hasClockOffset()) {
            if (System.nanoTime() >= deadline) {
                return false;
            }
            Thread.sleep(10);
        }
        tester.setJoiningRun(true);
        return true;
    }

    /** Returns the members that said they are testers ready to join the next run this tester starts. */
    public List<String> ready() {
        List<String> ready = new ArrayList<>();
        tester.getMembersServedChannels().forEach((member, served) -> {
            if (served.joinsRun() && dtron.getMembers().contains(member)) {
                ready.add(member);
            }
        });
        return ready;
    }

    /**
     * Waits until at least {@code count} testers said they are ready to join the next run this tester starts.
     *
     * @return whether they did, before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public boolean awaitReady(int count, Duration timeout) throws InterruptedException {
        long deadline = System.nanoTime() + timeout.toNanos();
        while (ready().size() < count) {
            if (System.nanoTime() >= deadline) {
                return false;
            }
            Thread.sleep(20);
        }
        return true;
    }

    /** This tester announces a run of several: the testers ready now are its testers. */
    public void announce() {
        joiners = Set.copyOf(ready());
        verdicts.clear();
    }

    /**
     * On a joining tester: waits for the run start of the tester that starts the run.
     *
     * @return the start; null if none came before the timeout
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public IDtronChannelValued awaitStart(Duration timeout) throws InterruptedException {
        IDtronChannelValued start = starts.poll(timeout.toNanos(), TimeUnit.NANOSECONDS);
        if (start != null) {
            verdicts.clear();
        }
        return start;
    }

    /** The run starts: a joining tester's leader is the tester that starts the runs on the bus. */
    public void runStarts() {
        leader = joining ? dtron.getTester().orElse(null) : null;
    }

    /** The run starts unannounced: a run of this tester alone. */
    public void alone() {
        joiners = Set.of();
    }

    /** For a joining tester, the tester that started the run it joined; null otherwise. */
    public String leader() {
        return leader;
    }

    /** Whether this run has other testers: it joined one, or others joined it. */
    public boolean several() {
        return joining || !joiners.isEmpty();
    }

    /** Whether a member is another tester of this run. */
    public boolean isPeer(String member) {
        return joiners.contains(member) || joining && member.equals(dtron.getTester().orElse(null))
                || Optional.ofNullable(tester.getMembersServedChannels().get(member)).map(ServedChannels::joinsRun)
                        .orElse(false);
    }

    /**
     * Another tester of the run told its verdict.
     *
     * @return the verdict's exit code
     */
    public int told(IDtronChannelValued message) {
        int verdict = message.getVariables().get("verdict");
        verdicts.put(message.getSender(), verdict);
        return verdict;
    }

    /** Tells the other testers this one's verdict. */
    public void tell(int verdictExitCode) {
        try {
            dtron.send(Dtron.RUN_VERDICT.constructValued(Map.of("verdict", verdictExitCode)));
        } catch (DtronException | IllegalStateException e) {
            LOG.warn("Cannot tell the other testers the verdict: {}", e.getMessage());
        }
    }

    /** Waits, {@code timeout} at most, until every tester that joined told its verdict or left. */
    public void awaitVerdicts(Duration timeout) {
        long deadline = System.nanoTime() + timeout.toNanos();
        while (!joiners.stream().allMatch(m -> verdicts.containsKey(m) || !dtron.getMembers().contains(m))
                && System.nanoTime() < deadline) {
            try {
                Thread.sleep(10);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                break;
            }
        }
    }

    /** Returns the verdicts the other testers of the run told, as exit codes by member. */
    public Map<String, Integer> verdicts() {
        return Collections.unmodifiableMap(new TreeMap<>(verdicts));
    }
}
