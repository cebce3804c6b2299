package io.dtron.bridge.internal;

import io.dtron.api.Dtron;
import io.dtron.api.MemberDelay;
import io.dtron.api.internal.TesterSide;
import io.dtron.bridge.BusRun;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeSet;
import java.util.function.Predicate;
import java.util.function.Supplier;

/**
 * Not API. A tester's probes of the adapter members before a run: the delays of their messages ({@link #measure}),
 * and rounds of probes through the way of an input until their round trips are steady ({@link #untilSteady}), which
 * set how long an input takes to reach each member ({@link InputDelays#probed}). The testers of other runs and of
 * this run are no adapters and are not probed.
 */
public final class AdapterProbes {
    /** How long an adapter member gets to answer a probe. */
    public static final Duration PROBE_TIMEOUT = Duration.ofSeconds(1);
    /** How long {@link #measure} waits for a member's first message with a clock offset estimate. */
    static final Duration FIRST_ESTIMATE_TIMEOUT = Duration.ofSeconds(2);

    private final Dtron dtron;
    private final TesterSide tester;
    private final InputDelays inputDelays;
    private final Supplier<Set<String>> testersOfOtherRuns;
    private final Predicate<String> peerTester;

    /**
     * The probes of {@code dtron}'s tester side, keeping the probes' round trips in {@code inputDelays}.
     *
     * @param testersOfOtherRuns the testers on the bus whose runs are not this run's
     * @param peerTester         whether a member is another tester of this run
     */
    public AdapterProbes(Dtron dtron, TesterSide tester, InputDelays inputDelays,
            Supplier<Set<String>> testersOfOtherRuns, Predicate<String> peerTester) {
        this.dtron = dtron;
        this.tester = tester;
        this.inputDelays = inputDelays;
        this.testersOfOtherRuns = testersOfOtherRuns;
        this.peerTester = peerTester;
    }

    /**
     * The delays measured: asks every adapter member {@code rounds} times, {@code spacing} apart, to answer, and sums
     * up every message of theirs measured so far (a member that joined just now is given {@link
     * #FIRST_ESTIMATE_TIMEOUT} to send its first clock offset estimate, without which its delays cannot be measured).
     *
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public BusRun.Delays measure(int rounds, Duration spacing) throws InterruptedException {
        Set<String> adapters = new HashSet<>(dtron.getMembers());
        adapters.remove(dtron.getMemberId());
        adapters.removeAll(testersOfOtherRuns.get());
        // a member that joined just now sends its first clock offset estimate after a few round trips
        long deadline = System.nanoTime() + FIRST_ESTIMATE_TIMEOUT.toNanos();
        while (!tester.getDelaysFromMembers().keySet().containsAll(adapters) && System.nanoTime() < deadline) {
            Thread.sleep(10);
        }
        for (int i = 0; i < rounds && !adapters.isEmpty(); i++) {
            tester.probe(adapters, PROBE_TIMEOUT);
            Thread.sleep(spacing.toMillis());
        }
        long max = 0;
        long error = 0;
        long messages = 0;
        int members = 0;
        for (Map.Entry<String, MemberDelay> e : tester.getDelaysFromMembers().entrySet()) {
            if (adapters.contains(e.getKey())) {
                max = Math.max(max, e.getValue().maxNanos());
                error = Math.max(error, e.getValue().maxErrorNanos());
                messages += e.getValue().count();
                members++;
            }
        }
        return new BusRun.Delays(max, error, messages, members);
    }

    /**
     * Probes every adapter member in rounds, {@code spacing} apart (zero: one after the other), for at least {@code
     * minimum} and until the round trips of the last rounds are steady and no longer get faster, or {@code limit} has
     * passed (see {@link InputDelays#steady} and {@link InputDelays#noLongerImproving}). Each probe takes the way of an
     * input ({@link TesterSide#probeAsInput}). Each member's longest round trip in the last rounds is kept as the
     * delay of the inputs it receives ({@link InputDelays#probed}).
     *
     * @throws InterruptedException if the thread was interrupted while waiting
     */
    public BusRun.Probing untilSteady(Duration spacing, Duration minimum, Duration limit) throws InterruptedException {
        long start = System.nanoTime();
        Set<String> adapters = new TreeSet<>(dtron.getMembers());
        adapters.remove(dtron.getMemberId());
        adapters.removeAll(testersOfOtherRuns.get());
        adapters.removeAll(tester.getOtherTesters());
        Map<String, List<Long>> byMember = new HashMap<>();
        List<Long> rounds = new ArrayList<>();
        boolean steady = false;
        while (!adapters.isEmpty()) {
            long round = 0;
            for (String member : adapters) {
                long sent = System.nanoTime();
                Set<String> answered = tester.probeAsInput(Set.of(member), PROBE_TIMEOUT);
                long micros = answered.contains(member) ? (System.nanoTime() - sent) / 1000 : PROBE_TIMEOUT.toNanos()
                        / 1000;
                byMember.computeIfAbsent(member, m -> new ArrayList<>()).add(micros);
                round = Math.max(round, micros);
            }
            rounds.add(round);
            long elapsed = System.nanoTime() - start;
            steady = InputDelays.steady(rounds) && InputDelays.noLongerImproving(rounds);
            if (steady && elapsed >= minimum.toNanos() || elapsed >= limit.toNanos()) {
                break;
            }
            if (!spacing.isZero()) {
                Thread.sleep(spacing.toMillis());
            }
        }
        byMember.forEach((member, trips) -> inputDelays.probed(member, trips.subList(Math.max(0, trips.size()
                - InputDelays.STEADY_ROUNDS), trips.size()).stream().mapToLong(Long::longValue).max().orElse(0)));
        long last = rounds.subList(Math.max(0, rounds.size() - InputDelays.STEADY_ROUNDS), rounds.size()).stream()
                .mapToLong(Long::longValue).max().orElse(0);
        return new BusRun.Probing(rounds.size(), steady, last, (System.nanoTime() - start) / 1_000_000);
    }

    /**
     * The room an input on {@code channel} needs before its window's end: for inputs sent at their time, how long one
     * may take to reach the system, the longer of the probe round trip before the run of the adapters that receive it
     * and the 99th percentile of the delays of its inputs acknowledged so far (see {@link InputDelays#roomMicros}),
     * 0 before anything was measured; for inputs sent ahead ({@link #inputLeadMicros}), how late after their due
     * time the adapters applied them ({@link InputDelays#heldRoomMicros}).
     */
    public long inputDelayMicros(String channel) {
        List<String> receivers = receivers(channel);
        return holdInputs(receivers) ? inputDelays.heldRoomMicros(channel)
                : inputDelays.roomMicros(channel, receivers);
    }

    /**
     * How far ahead of its time an input on {@code channel} is sent: when every adapter member that receives it holds
     * inputs until they are due ({@link TesterSide#holdsInputs}), the way an input takes to them ({@link
     * InputDelays#roomMicros}); else 0, and inputs are sent at their time.
     */
    public long inputLeadMicros(String channel) {
        List<String> receivers = receivers(channel);
        return holdInputs(receivers) ? inputDelays.roomMicros(channel, receivers) : 0;
    }

    /** Whether inputs of a channel received by {@code receivers} are sent ahead: there are some, and all hold them. */
    private boolean holdInputs(List<String> receivers) {
        return !receivers.isEmpty() && receivers.stream().allMatch(tester::holdsInputs);
    }

    /** The adapter members that receive {@code channel}, as they said in the handshake. */
    private List<String> receivers(String channel) {
        List<String> receivers = new ArrayList<>();
        tester.getMembersServedChannels().forEach((member, served) -> {
            if (served.receives().contains(channel) && !peerTester.test(member)) {
                receivers.add(member);
            }
        });
        return receivers;
    }
}
