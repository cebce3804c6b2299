package io.dtron.engine.internal.verify;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.PartitionException;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.verify.TestabilityReport;
import io.dtron.engine.verify.TestabilityReport.Check;
import io.dtron.engine.verify.TestabilityReport.Problem;
import io.dtron.engine.verify.VerificationResult.Statistics;
import io.dtron.engine.verify.VerifierOptions;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.Edge;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.HashMap;
import java.util.List;
import java.util.Map;

/**
 * The testability checks of a model with its test interface (see {@link io.dtron.engine.verify.Verifier#testability}),
 * each a search DTRON builds itself on the zone graph (Extra+_M), with the searches and traces of a {@link Checker}:
 * <ul>
 * <li>on the implementation closed by a generated {@link CanonicalTester}: input enabledness (the target's
 * invariant included), connectedness (no deadlock, every location of the implementation reachable) and strong
 * responsiveness (no reachable cycle of internal moves);</li>
 * <li>on the model as written, with its own environment: time-lock freedom, the coverage of the
 * implementation's locations by that environment, and cycles of moves that take no time (Zeno);</li>
 * <li>on the processes' structure: output observability, and cycles that are not strongly non-Zeno.</li>
 * </ul>
 */
public final class TestabilityChecker {
    private static final int MAX_PROBLEMS = 3;
    private static final String OBSERVABILITY = "output observability";
    private static final String INPUTS = "input enabledness";
    private static final String CONNECTEDNESS = "connectedness";
    private static final String COVERAGE = "environment coverage";
    private static final String RESPONSIVENESS = "strong responsiveness";
    private static final String TIMELOCK = "time-lock freedom";

    private final Checker checker;
    private final Network network;
    private final VerifierOptions options;
    private final Semantics semantics;

    /** The testability checks of the network {@code checker} checks. */
    public TestabilityChecker(Checker checker) {
        this.checker = checker;
        this.network = checker.network();
        this.options = checker.options();
        this.semantics = checker.semantics();
    }

    /** The testability checks; see {@link io.dtron.engine.verify.Verifier#testability}. */
    public TestabilityReport testability(TestInterface testInterface) {
        List<Problem> observability = new ArrayList<>();
        Partition partition;
        try {
            partition = Partition.of(network, testInterface);
        } catch (PartitionException e) {
            observability.add(new Problem(e.getMessage(), null));
            String notRun = "not checked: the model does not split into environment and implementation";
            List<Check> checks = new ArrayList<>(List.of(new Check(OBSERVABILITY, observability, null)));
            for (String name : List.of(INPUTS, CONNECTEDNESS, COVERAGE, RESPONSIVENESS, TIMELOCK, "Zeno freedom")) {
                checks.add(new Check(name, List.of(), notRun));
            }
            return new TestabilityReport(checks, Statistics.NONE);
        }
        boolean[] sends = channelsSentByImplementation(partition);
        for (TestInterface.ObservableChannel o : testInterface.outputs()) {
            if (!sends[o.channel()]) {
                observability.add(new Problem("the implementation never sends the output "
                        + o.name() + " (" + network.channelName(o.channel()) + ")", null));
            }
        }
        Budget budget = new Budget("testability", options.timeLimit(), options.memoryLimitBytes(),
                options.progressInterval());
        try {
            CanonicalTester tester = CanonicalTester.of(network, partition, testInterface);
            WithTester withTester = new WithTester(tester, testInterface);
            String unknown = withTester.explore(budget);
            long stored = budget.stored;
            WithEnvironment withEnvironment = new WithEnvironment(withTester.reached);
            String unknownClosed = unknown != null ? unknown : withEnvironment.explore(budget);
            budget.stored += stored;
            String partly = tester.notes().isEmpty() ? null : "partly: " + String.join("; ", tester.notes());
            return new TestabilityReport(List.of(
                    new Check(OBSERVABILITY, observability, null),
                    new Check(INPUTS, withTester.refusals, note(unknown, partly, "in every reachable state where"
                            + " time may pass, for every valuation and every value of its variables, the"
                            + " implementation takes each input to a state whose invariant holds")),
                    new Check(CONNECTEDNESS, withTester.connectedness(unknown == null), note(unknown, partly, "with a canonical"
                            + " tester that offers every input at any time and takes every output at once: no"
                            + " deadlock, and every location of the implementation reachable")),
                    new Check(COVERAGE, unknownClosed == null ? withEnvironment.uncovered() : List.of(), note(unknownClosed, null, "the model's own"
                            + " environment, which chooses the inputs of a test run, leads the implementation to every"
                            + " location a canonical tester reaches")),
                    new Check(RESPONSIVENESS, withTester.cycles, note(unknown, partly, "with a canonical tester: no"
                            + " reachable cycle of internal moves of the implementation, which could run for ever"
                            + " without an input or an output")),
                    new Check(TIMELOCK, withEnvironment.timelocks, note(unknownClosed, null, null)),
                    zenoCheck(withEnvironment.zeroTime, unknownClosed)), checker.statistics(budget));
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while checking testability: " + e.format());
        }
    }

    private static String note(String unknown, String partly, String meaning) {
        return unknown != null ? "unknown: " + unknown : partly != null ? partly : meaning;
    }

    /** The exploration of the implementation with a canonical tester. */
    private final class WithTester {
        final CanonicalTester tester;
        final Checker composed;
        final ZoneGraph graph;
        final Semantics sem;
        final List<TestInterface.ObservableChannel> inputs;
        final boolean[] isInput;
        /** Per process of the model (environment processes: null), the locations reached. */
        final boolean[][] reached = new boolean[network.processes().size()][];
        /** Per process of the composition, the model's process number. */
        final int[] original;
        final List<Problem> refusals = new ArrayList<>();
        final List<Problem> deadlocks = new ArrayList<>();
        final List<Problem> cycles = new ArrayList<>();

        WithTester(CanonicalTester tester, TestInterface testInterface) {
            this.tester = tester;
            this.composed = new Checker(tester.network(), options);
            this.graph = composed.graph(true, List.of());
            this.sem = composed.semantics();
            this.inputs = testInterface.inputs();
            this.isInput = new boolean[network.channelCount()];
            inputs.forEach(i -> isInput[i.channel()] = true);
            this.original = new int[tester.network().processes().size()];
            for (Process p : tester.network().processes()) {
                if (p.index() != tester.tester()) {
                    original[p.index()] = network.process(p.name()).orElseThrow().index();
                    reached[original[p.index()]] = new boolean[p.locations().size()];
                }
            }
        }

        /** Explores; null, or why it stopped before the end. */
        String explore(Budget budget) {
            try {
                CycleSearch internal = new CycleSearch((s, sink) -> graph.successors(s, (m, next) -> {
                    if (m.steps().stream().noneMatch(step -> step.process() == tester.tester())) {
                        sink.accept(m, next);
                    }
                }), budget);
                composed.search(graph, null, graph::deadlocked, budget, (n, s) -> {
                    for (int p = 0; p < original.length; p++) {
                        if (p != tester.tester() && s.location(p) >= 0) {
                            reached[original[p]][s.location(p)] = true;
                        }
                    }
                    if (refusals.size() < MAX_PROBLEMS && sem.mayDelay(s)) {
                        refusals(n, s);
                    }
                    if (deadlocks.size() < MAX_PROBLEMS) {
                        List<Dbm> dead = graph.deadlocked(s);
                        if (!dead.isEmpty()) {
                            String message = "deadlock with the canonical tester in " + locations(s)
                                    + when(dead.get(0), composed) + ": the implementation takes no input and does"
                                    + " nothing, now or after any delay";
                            if (deadlocks.stream().noneMatch(p -> p.message().equals(message))) {
                                deadlocks.add(new Problem(message, composed.trace(graph, Checker.path(n), dead.get(0),
                                        -1, null, null)));
                            }
                        }
                    }
                    if (cycles.isEmpty()) {
                        Checker.Lasso lasso = internal.from(s);
                        if (lasso != null) {
                            cycles.add(new Problem("the implementation can move for ever without an input or an"
                                    + " output: a cycle of internal moves from " + locations(lasso.states().get(
                                    lasso.loopStart())), composed.trace(graph, Checker.path(n), lasso)));
                        }
                    }
                    return null;
                });
                return null;
            } catch (Budget.LimitReached e) {
                return e.getMessage();
            }
        }

        /** Adds the inputs the implementation refuses somewhere in {@code s}, a state of node {@code n}. */
        private void refusals(Checker.Node n, SymState s) {
            int[] vars = graph.vars(s);
            Map<String, List<Dbm>> accepted = new HashMap<>();
            sem.moves(s, c -> c >= 0 && isInput[c], (move, next) -> {
                int[] frame = null;
                boolean implementation = false;
                for (Semantics.Step step : move.steps()) {
                    if (step.process() == tester.tester()) {
                        frame = step.frame();
                    } else {
                        implementation = true;
                    }
                }
                Dbm enabled = implementation && frame != null ? graph.enablingZone(s, vars, move, next.zone()) : null;
                if (enabled != null) {
                    accepted.computeIfAbsent(key(move.channel(), frame), k -> new ArrayList<>()).add(enabled);
                }
            });
            Process testerProcess = tester.network().processes().get(tester.tester());
            for (int i = 0; i < inputs.size() && refusals.size() < MAX_PROBLEMS; i++) {
                Edge offer = testerProcess.edges().get(i);
                for (int[] frame : frames(offer)) {
                    List<Dbm> refused = new ArrayList<>(List.of(s.zone()));
                    for (Dbm z : accepted.getOrDefault(key(inputs.get(i).channel(), frame), List.of())) {
                        refused = Zones.subtract(refused, z);
                    }
                    if (!refused.isEmpty()) {
                        String message = "the implementation does not accept the input " + inputs.get(i).name()
                                + values(offer, frame) + " in " + locations(s) + when(refused.get(0), composed);
                        if (refusals.stream().noneMatch(p -> p.message().equals(message))) {
                            refusals.add(new Problem(message, composed.trace(graph, Checker.path(n), refused.get(0),
                                    -1, null, null)));
                        }
                        break;
                    }
                }
            }
        }

        private static String key(int channel, int[] frame) {
            return channel + Arrays.toString(frame);
        }

        /** The implementation's locations in {@code s}. */
        private String locations(SymState s) {
            List<String> out = new ArrayList<>();
            for (Process p : tester.network().processes()) {
                if (p.index() != tester.tester() && s.location(p.index()) >= 0) {
                    out.add(p.name() + "." + p.locations().get(s.location(p.index())).name());
                }
            }
            return String.join(", ", out);
        }

        /** Deadlocks, then, when the exploration was {@code complete}, the locations no tester leads to. */
        List<Problem> connectedness(boolean complete) {
            List<Problem> out = new ArrayList<>(deadlocks);
            for (Process p : complete ? network.processes() : List.<Process>of()) {
                for (int l = 0; reached[p.index()] != null && l < reached[p.index()].length; l++) {
                    if (!reached[p.index()][l]) {
                        out.add(new Problem(p.name() + "." + p.locations().get(l).name() + " is unreachable, even"
                                + " with a tester that offers every input at any time", null));
                    }
                }
            }
            return out;
        }
    }

    /** " when x>3" for a zone part, "" for the whole of the clock space. */
    private static String when(Dbm part, Checker on) {
        String zone = part.toString(on.clockNames());
        return zone.equals("true") ? "" : " when " + zone;
    }

    /** " with amount=3" for an offer with select values, "" for one without. */
    private static String values(Edge offer, int[] frame) {
        List<String> out = new ArrayList<>();
        for (Edge.Select sel : offer.selects()) {
            out.add(sel.name() + "=" + frame[sel.slot()]);
        }
        return out.isEmpty() ? "" : " with " + String.join(", ", out);
    }

    /** The exploration of the model as written, with its own environment. */
    private final class WithEnvironment {
        final boolean[][] reachable;
        final boolean[][] reached = new boolean[network.processes().size()][];
        final List<Problem> timelocks = new ArrayList<>();
        final List<Problem> zeroTime = new ArrayList<>();

        WithEnvironment(boolean[][] reachable) {
            this.reachable = reachable;
            for (Process p : network.processes()) {
                reached[p.index()] = new boolean[p.locations().size()];
            }
        }

        /** Explores; null, or why it stopped before the end. */
        String explore(Budget budget) {
            ZoneGraph graph = checker.graph(true, List.of());
            try {
                CycleSearch instant = new CycleSearch((s, sink) -> semantics.moves(s, sink::accept), budget);
                checker.search(graph, null, graph::deadlocked, budget, (n, s) -> {
                    for (Process p : network.processes()) {
                        if (s.location(p.index()) >= 0) {
                            reached[p.index()][s.location(p.index())] = true;
                        }
                    }
                    if (timelocks.size() < MAX_PROBLEMS) {
                        List<Dbm> dead = graph.deadlocked(s);
                        if (!dead.isEmpty() && !graph.timeDiverges(s)) {
                            timelocks.add(new Problem("time cannot pass and nothing can happen in "
                                    + describeLocations(s) + when(dead.get(0), checker),
                                    checker.trace(graph, Checker.path(n), dead.get(0), -1, null, null)));
                        }
                    }
                    if (zeroTime.isEmpty()) {
                        Checker.Lasso lasso = instant.from(s);
                        if (lasso != null) {
                            zeroTime.add(new Problem("a cycle of moves can run for ever with no time passing, from "
                                    + describeLocations(lasso.states().get(lasso.loopStart())),
                                    checker.trace(graph, Checker.path(n), lasso)));
                        }
                    }
                    return null;
                });
                return null;
            } catch (Budget.LimitReached e) {
                return e.getMessage();
            }
        }

        /** The implementation's locations a canonical tester reaches but the model's environment does not. */
        List<Problem> uncovered() {
            List<Problem> out = new ArrayList<>();
            for (Process p : network.processes()) {
                for (int l = 0; reachable[p.index()] != null && l < reachable[p.index()].length; l++) {
                    if (reachable[p.index()][l] && !reached[p.index()][l]) {
                        out.add(new Problem("the model's environment never leads the implementation to " + p.name()
                                + "." + p.locations().get(l).name(), null));
                    }
                }
            }
            return out;
        }
    }

    /**
     * Zeno freedom: the cycles of the model's zone graph that take no time (found, with a trace), then the cycles
     * of the processes that are not strongly non-Zeno (which may take no time, or ever less time).
     */
    private Check zenoCheck(List<Problem> zeroTime, String unknown) {
        List<Problem> zeno = new ArrayList<>(zeroTime);
        for (Process p : network.processes()) {
            List<String> cycle = ZenoCycles.possiblyZeno(p, semantics.dimension());
            if (cycle != null) {
                zeno.add(new Problem("the cycle " + String.join(" -> ", cycle) + " of " + p.name()
                        + " may take no time: no clock is both reset and bounded from below on it", null));
            }
        }
        return new Check("Zeno freedom", zeno, note(unknown, null, "no reachable cycle of the zone graph runs"
                + " without time passing, and, structurally, on every cycle of every process a clock is reset and"
                + " compared with x > c or x >= c, c > 0"));
    }

    /** The channels the implementation's edges may send on (all elements of a channel array indexed by data). */
    private boolean[] channelsSentByImplementation(Partition partition) {
        boolean[] sends = new boolean[network.channelCount()];
        for (Process p : network.processes()) {
            if (partition.isEnvironment(p.index())) {
                continue;
            }
            for (Edge e : p.edges()) {
                if (e.sync() == null || e.sync().direction() != Edge.Direction.SEND) {
                    continue;
                }
                io.dtron.model.Expression c = e.sync().channel();
                while (c instanceof io.dtron.model.Expression.Index i) {
                    c = i.array();
                }
                if (c instanceof io.dtron.model.Expression.ChannelRef ref) {
                    int first = ref.channel().index();
                    for (int k = first; k < first + ref.channel().type().channels(); k++) {
                        sends[k] = true;
                    }
                }
            }
        }
        return sends;
    }

    /** Every binding of an edge's selects, as frames. */
    private static List<int[]> frames(Edge e) {
        List<int[]> out = new ArrayList<>();
        int[] frame = new int[e.frameSize()];
        List<Edge.Select> selects = e.selects();
        for (Edge.Select sel : selects) {
            frame[sel.slot()] = sel.lower();
        }
        while (true) {
            out.add(frame.clone());
            int k = selects.size() - 1;
            while (k >= 0 && frame[selects.get(k).slot()] == selects.get(k).upper()) {
                frame[selects.get(k).slot()] = selects.get(k).lower();
                k--;
            }
            if (k < 0) {
                return out;
            }
            frame[selects.get(k).slot()]++;
        }
    }

    /** Every process's location in {@code s}, for messages. */
    private String describeLocations(SymState s) {
        List<String> out = new ArrayList<>();
        for (Process p : network.processes()) {
            int l = s.location(p.index());
            if (l >= 0) {
                out.add(p.name() + "." + p.locations().get(l).name());
            }
        }
        return String.join(", ", out);
    }
}
