package io.dtron.engine.internal.verify;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.PartitionException;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.verify.TestabilityReport;
import io.dtron.engine.verify.VerificationResult.Statistics;
import io.dtron.engine.verify.VerifierOptions;
import io.dtron.engine.zone.Dbm;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.TestInterface;
import java.util.ArrayList;
import java.util.List;

/**
 * The testability checks of a model with its test interface (see {@link io.dtron.engine.verify.Verifier#testability}),
 * on the searches and traces of a {@link Checker}.
 */
public final class TestabilityChecker {
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

    private static final int MAX_PROBLEMS = 3;

    /** The testability checks; see {@link io.dtron.engine.verify.Verifier#testability}. */
    public TestabilityReport testability(TestInterface testInterface) {
        Budget budget = new Budget("testability", options.timeLimit(), options.memoryLimitBytes(),
                options.progressInterval());
        List<TestabilityReport.Problem> observability = new ArrayList<>();
        Partition partition;
        try {
            partition = Partition.of(network, testInterface);
        } catch (PartitionException e) {
            observability.add(new TestabilityReport.Problem(e.getMessage(), null));
            String notRun = "not checked: the model does not split into environment and implementation";
            return new TestabilityReport(List.of(
                    new TestabilityReport.Check("output observability", observability, null),
                    new TestabilityReport.Check("input enabledness", List.of(), notRun),
                    new TestabilityReport.Check("connectedness", List.of(), notRun),
                    new TestabilityReport.Check("time-lock freedom", List.of(), notRun),
                    new TestabilityReport.Check("Zeno freedom", List.of(), notRun)), Statistics.NONE);
        }
        boolean[] sends = channelsSentByImplementation(partition);
        for (TestInterface.ObservableChannel o : testInterface.outputs()) {
            if (!sends[o.channel()]) {
                observability.add(new TestabilityReport.Problem("the implementation never sends the output "
                        + o.name() + " (" + network.channelName(o.channel()) + ")", null));
            }
        }
        ZoneGraph graph = checker.graph(true, List.of());
        List<TestabilityReport.Problem> inputs = new ArrayList<>();
        List<TestabilityReport.Problem> timelocks = new ArrayList<>();
        boolean[][] reached = new boolean[network.processes().size()][];
        for (Process p : network.processes()) {
            reached[p.index()] = new boolean[p.locations().size()];
        }
        try {
            checker.search(graph, null, graph::deadlocked, budget, (n, s) -> {
                for (Process p : network.processes()) {
                    if (s.location(p.index()) >= 0) {
                        reached[p.index()][s.location(p.index())] = true;
                    }
                }
                if (inputs.size() < MAX_PROBLEMS && semantics.mayDelay(s)) {
                    for (TestInterface.ObservableChannel i : testInterface.inputs()) {
                        List<Dbm> refused = refused(s, i.channel(), partition);
                        if (!refused.isEmpty() && inputs.size() < MAX_PROBLEMS) {
                            inputs.add(new TestabilityReport.Problem("the implementation does not accept the input "
                                    + i.name() + " in " + describeLocations(s, partition, false) + " when "
                                    + refused.get(0).toString(checker.clockNames()), checker.trace(graph, Checker.path(n), s.zone(), -1, null,
                                    null)));
                        }
                    }
                }
                if (timelocks.size() < MAX_PROBLEMS) {
                    List<Dbm> dead = graph.deadlocked(s);
                    if (!dead.isEmpty() && !graph.timeDiverges(s)) {
                        timelocks.add(new TestabilityReport.Problem("time cannot pass and nothing can happen in "
                                + describeLocations(s, partition, true) + " when " + dead.get(0).toString(checker.clockNames()),
                                checker.trace(graph, Checker.path(n), dead.get(0), -1, null, null)));
                    }
                }
                return null;
            });
        } catch (Budget.LimitReached e) {
            String unknown = "unknown: " + e.getMessage();
            return new TestabilityReport(List.of(
                    new TestabilityReport.Check("output observability", observability, null),
                    new TestabilityReport.Check("input enabledness", inputs, unknown),
                    new TestabilityReport.Check("connectedness", List.of(), unknown),
                    new TestabilityReport.Check("time-lock freedom", timelocks, unknown),
                    zenoCheck()), checker.statistics(budget));
        } catch (ModelRuntimeException e) {
            throw new UnsupportedModelException("model error while checking testability: " + e.format());
        }
        List<TestabilityReport.Problem> unreached = new ArrayList<>();
        for (Process p : network.processes()) {
            if (partition.isEnvironment(p.index())) {
                continue;
            }
            for (int l = 0; l < reached[p.index()].length; l++) {
                if (!reached[p.index()][l]) {
                    unreached.add(new TestabilityReport.Problem("the environment never leads the implementation to "
                            + p.name() + "." + p.locations().get(l).name(), null));
                }
            }
        }
        return new TestabilityReport(List.of(
                new TestabilityReport.Check("output observability", observability, null),
                new TestabilityReport.Check("input enabledness", inputs, "in every reachable state where time may"
                        + " pass, for every valuation, some receiving edge of the implementation has its guard true"
                        + " (the target's invariant is not checked)"),
                new TestabilityReport.Check("connectedness", unreached, "with the model's own environment"),
                new TestabilityReport.Check("time-lock freedom", timelocks, null),
                zenoCheck()), checker.statistics(budget));
    }

    private TestabilityReport.Check zenoCheck() {
        List<TestabilityReport.Problem> zeno = new ArrayList<>();
        for (Process p : network.processes()) {
            List<String> cycle = ZenoCycles.possiblyZeno(p, semantics.dimension());
            if (cycle != null) {
                zeno.add(new TestabilityReport.Problem("the cycle " + String.join(" -> ", cycle) + " of " + p.name()
                        + " may take no time: no clock is both reset and bounded from below on it", null));
            }
        }
        return new TestabilityReport.Check("Zeno freedom", zeno, "structural: a cycle passes when a clock is reset"
                + " on it and compared with x > c or x >= c, c > 0, on it");
    }

    /** The channels the implementation's edges may send on (all elements of a channel array indexed by data). */
    private boolean[] channelsSentByImplementation(Partition partition) {
        boolean[] sends = new boolean[network.channelCount()];
        for (Process p : network.processes()) {
            if (partition.isEnvironment(p.index())) {
                continue;
            }
            for (io.dtron.model.Edge e : p.edges()) {
                if (e.sync() == null || e.sync().direction() != io.dtron.model.Edge.Direction.SEND) {
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

    /** The valuations of {@code s}'s zone where no receiving edge of the implementation takes {@code channel}. */
    private List<Dbm> refused(SymState s, int channel, Partition partition) {
        List<Dbm> refused = new ArrayList<>(List.of(s.zone()));
        int[] vars = new int[network.stateSize()];
        for (int i = 0; i < vars.length; i++) {
            vars[i] = s.var(i);
        }
        for (Process p : network.processes()) {
            int l = s.location(p.index());
            if (partition.isEnvironment(p.index()) || l < 0) {
                continue;
            }
            for (io.dtron.model.Edge e : p.edges()) {
                if (e.source() != l || e.sync() == null
                        || e.sync().direction() != io.dtron.model.Edge.Direction.RECEIVE) {
                    continue;
                }
                for (int[] frame : frames(e)) {
                    if (semantics.evaluator().channel(e.sync().channel(), vars, frame) != channel
                            || e.guard() != null && !semantics.evaluator().dataHolds(e.guard(), vars, frame)) {
                        continue;
                    }
                    Dbm accepted = s.zone().copy();
                    if (e.guard() == null || semantics.evaluator().constrain(e.guard(), vars, frame, accepted, 1)) {
                        refused = Zones.subtract(refused, accepted);
                        if (refused.isEmpty()) {
                            return refused;
                        }
                    }
                }
            }
        }
        return refused;
    }

    /** Every binding of an edge's selects, as frames. */
    private static List<int[]> frames(io.dtron.model.Edge e) {
        List<int[]> out = new ArrayList<>();
        int[] frame = new int[e.frameSize()];
        List<io.dtron.model.Edge.Select> selects = e.selects();
        for (io.dtron.model.Edge.Select sel : selects) {
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

    private String describeLocations(SymState s, Partition partition, boolean all) {
        List<String> out = new ArrayList<>();
        for (Process p : network.processes()) {
            int l = s.location(p.index());
            if (l >= 0 && (all || !partition.isEnvironment(p.index()))) {
                out.add(p.name() + "." + p.locations().get(l).name());
            }
        }
        return String.join(", ", out);
    }
}
