package io.dtron.bridge.internal;

import io.dtron.api.Dtron;
import io.dtron.api.ServedChannels;
import io.dtron.api.internal.TesterSide;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Collections;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeMap;
import java.util.concurrent.ConcurrentHashMap;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. Who is on the bus for a run before it starts, as the channel-serving handshake tells: which channels of the
 * model no adapter serves yet, what each adapter serves, the testers of other runs (and which of them joined the bus
 * first), and the adapters a tester waited for, which must still be there when the run starts.
 */
public final class RunMembers {
    private static final Logger LOG = LoggerFactory.getLogger(RunMembers.class);
    /** How long a tester waits for every member on the bus to tell whether it is a tester. */
    static final Duration ROLL_CALL = Duration.ofSeconds(3);

    private final Dtron dtron;
    private final TesterSide tester;
    private final Set<String> inputs;
    private final Set<String> outputs;
    private final boolean joining;
    /** The adapters the tester waited for ({@link #expectAdapters}): each must still be there at the start. */
    private final Set<String> expected = ConcurrentHashMap.newKeySet();
    /** Whether every channel of the model was served by the handshake when {@link #expectAdapters} was called. */
    private volatile boolean expectedByHandshake;

    /**
     * The members of the runs of {@code dtron}'s tester of a model with these input and output channels, which
     * joins another tester's runs when {@code joining}.
     */
    public RunMembers(Dtron dtron, TesterSide tester, Set<String> inputs, Set<String> outputs, boolean joining) {
        this.dtron = dtron;
        this.tester = tester;
        this.inputs = Set.copyOf(inputs);
        this.outputs = Set.copyOf(outputs);
        this.joining = joining;
    }

    /**
     * The testers on the bus whose runs are not this run's: every other tester that greeted the bus, but, for a
     * joining tester, the one whose run it joins.
     */
    public Set<String> testersOfOtherRuns() {
        Set<String> testers = new HashSet<>(tester.getOtherTesters());
        if (joining) {
            dtron.getTester().ifPresent(testers::remove);
        }
        return testers;
    }

    /** Waits until at least {@code count} members other than this one and other testers are on the bus. */
    public boolean awaitAdapters(int count, Duration timeout) throws InterruptedException {
        long deadline = System.nanoTime() + timeout.toNanos();
        // testers of other runs are no adapters of this one
        while (dtron.getMembers().size() - 1 - tester.getOtherTesters().size() < count) {
            long left = deadline - System.nanoTime();
            if (left <= 0) {
                return false;
            }
            dtron.awaitMembers(dtron.getMembers().size() + 1, Duration.ofNanos(Math.min(left, 100_000_000L)));
        }
        return true;
    }

    /** The channels no adapter serves yet: "input NAME", "output NAME"; testers of other runs do not count. */
    public List<String> unservedChannels() {
        Set<String> receivers = new HashSet<>();
        Set<String> senders = new HashSet<>();
        Set<String> testers = testersOfOtherRuns();
        tester.getMembersServedChannels().forEach((member, served) -> {
            if (!testers.contains(member)) {
                receivers.addAll(served.receives());
                senders.addAll(served.sends());
            }
        });
        List<String> missing = new ArrayList<>();
        inputs.stream().filter(c -> !receivers.contains(c)).sorted().forEach(c -> missing.add("input " + c));
        outputs.stream().filter(c -> !senders.contains(c)).sorted().forEach(c -> missing.add("output " + c));
        return missing;
    }

    /** Waits until every channel of the model is served ({@link #unservedChannels()} is empty). */
    public boolean awaitChannelsServed(Duration timeout) throws InterruptedException {
        long deadline = System.nanoTime() + timeout.toNanos();
        while (!unservedChannels().isEmpty()) {
            if (System.nanoTime() >= deadline) {
                return false;
            }
            Thread.sleep(20);
        }
        return true;
    }

    /** What each adapter member said it serves, by member id (testers of other runs left out). */
    public Map<String, ServedChannels> servedChannels() {
        Map<String, ServedChannels> served = new TreeMap<>(tester.getMembersServedChannels());
        served.keySet().removeAll(testersOfOtherRuns());
        return Collections.unmodifiableMap(served);
    }

    /**
     * The testers of other runs that joined the bus before this one, once every other member has told whether it is
     * a tester ({@link #ROLL_CALL} at most).
     */
    public List<String> testersThatJoinedFirst() throws InterruptedException {
        long deadline = System.nanoTime() + ROLL_CALL.toNanos();
        while (!silentMembers().isEmpty() && System.nanoTime() < deadline) {
            Thread.sleep(20);
        }
        List<String> members = dtron.getMembers();
        Set<String> testers = testersOfOtherRuns();
        List<String> first = members.subList(0, Math.max(0, members.indexOf(dtron.getMemberId()))).stream()
                .filter(testers::contains).toList();
        List<String> later = members.stream().filter(testers::contains).filter(m -> !first.contains(m)).toList();
        if (!later.isEmpty()) {
            LOG.info("Testers {} joined bus after this one; they leave this run to it", later);
        }
        return first;
    }

    /** The other members that have not told yet whether they are testers. */
    private List<String> silentMembers() {
        Set<String> told = new HashSet<>(tester.getMembersServedChannels().keySet());
        told.addAll(tester.getOtherTesters());
        told.add(dtron.getMemberId());
        return dtron.getMembers().stream().filter(m -> !told.contains(m)).toList();
    }

    /** Remembers the adapters on the bus now (the members other than this one and other testers). */
    public void expectAdapters() {
        Set<String> testers = tester.getOtherTesters();
        expected.clear();
        dtron.getMembers().stream().filter(m -> !m.equals(dtron.getMemberId()) && !testers.contains(m))
                .forEach(expected::add);
        expectedByHandshake = unservedChannels().isEmpty();
    }

    /** An expected adapter left during the run: that is said then, not again at the start. */
    public void left(String member) {
        expected.remove(member);
    }

    /**
     * At the start: why the system under test may be gone, when an adapter the tester waited for is no longer
     * among {@code present} (when the handshake served every channel then, only if a channel is no longer served);
     * empty otherwise. Forgets the expected adapters.
     */
    public java.util.Optional<String> goneBeforeStart(Set<String> present) {
        List<String> gone = expected.stream().filter(m -> !present.contains(m)).sorted().toList();
        expected.clear();
        List<String> unserved = expectedByHandshake ? unservedChannels() : List.of();
        if (gone.isEmpty() || expectedByHandshake && unserved.isEmpty()) {
            return java.util.Optional.empty();
        }
        return java.util.Optional.of("adapter member" + (gone.size() == 1 ? " " : "s ") + String.join(", ", gone)
                + " left the bus before the run started (members now " + dtron.getMembers() + ")"
                + (unserved.isEmpty() ? "" : ", and no adapter serves " + String.join(", ", unserved) + " any more")
                + "; the system under test may be gone");
    }
}
