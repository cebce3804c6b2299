package io.dtron.engine.internal.tester;

import io.dtron.engine.GoalStatus;
import io.dtron.engine.Steering;
import io.dtron.engine.Strategy;
import io.dtron.engine.Verdict;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.verify.DiscreteGraph;
import io.dtron.engine.internal.verify.StateProperty;
import io.dtron.engine.verify.Query;
import io.dtron.model.Network;
import io.dtron.model.Process;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.BitSet;
import java.util.HashMap;
import java.util.List;
import java.util.Map;

/**
 * Steers a run toward its goals and the edges it has not covered: the reactive planner. Before the run it explores
 * the closed network once ({@link DiscreteGraph}, shared by the runs of one model) and finds the goals no path reaches; during the run it scores every
 * input the plan offers, and waiting, by the distances (in moves) from where each leads to the targets, within the
 * horizon: to the nearest open goal ({@link Strategy#GOAL}), or, for {@link Strategy#COVERAGE}, the fewest moves that
 * cover every edge, trap and goal left together when they are few ({@link CoverTable}), else the sum of the distances
 * to each; distances are kept per discrete state (per target, for good: the graph does not change) and
 * the scores of arcs until the targets change (a goal reached, an edge covered). It also follows the goals (reached, or no longer reachable from any state the system
 * may be in), the edges covered on inputs and outputs, and the system's choices for the fairness check.
 */
public final class Steerer {
    /** The most symbolic states the exploration before the run visits. */
    public static final int MAX_STATES = 200_000;

    private final Steering steering;
    private final Network network;
    private final Semantics semantics;
    private final Partition partition;
    private final DiscreteGraph graph;
    private final List<Query> goals;
    private final List<StateProperty> properties;
    /** The goals, then the traps ({@code E<> t[1]}, ...): those the coverage strategy steers to as well. */
    private final GoalStatus[] status;
    /** How many of {@link #status} are the user's goals; the rest are traps. */
    private final int userGoals;
    /** Per goal, the distance of each node to it. */
    private final int[][] goalDistance;
    /** The distance to the nearest open goal, per node; null when no goal is open. */
    private int[] openDistance;
    /** The edges on observable arcs of the graph: what coverage counts. */
    private final BitSet coverable = new BitSet();
    private final BitSet environmentEdges = new BitSet();
    private final BitSet covered = new BitSet();
    private long environmentCoveredMicros = -1;
    private int environmentCoveredInputs = -1;
    /** The system's choices: per node, how often each of its output arcs was taken. */
    private final Map<Integer, int[]> choices = new HashMap<>();
    /** The clock constants that matter per location, for how long waiting is worth it; null when unknown. */
    private final io.dtron.engine.internal.sem.ClockLimits limits;

    /** Why the steerer ends a run. */
    public record Stop(Verdict verdict, String explanation) {
    }

    private Steerer(Steering steering, Network network, Semantics semantics, Partition partition,
                    DiscreteGraph graph, List<Query> goals, List<StateProperty> properties, int userGoals) {
        this.userGoals = userGoals;
        this.steering = steering;
        this.network = network;
        this.semantics = semantics;
        this.partition = partition;
        this.graph = graph;
        this.goals = goals;
        this.properties = properties;
        this.limits = io.dtron.engine.internal.sem.ClockLimits.of(network, semantics.dimension(), List.of());
        this.status = new GoalStatus[goals.size()];
        this.goalDistance = new int[goals.size()][];
        for (int g = 0; g < goals.size(); g++) {
            goalDistance[g] = graph.distances(graph.goalNodes(g), null);
            boolean never = graph.complete() && graph.goalNodes(g).isEmpty();
            status[g] = never ? new GoalStatus(goals.get(g).text(), GoalStatus.State.UNREACHABLE, -1,
                    "the model checker finds no reachable state where it holds (" + graph.zoneStates()
                            + " symbolic states explored)")
                    : new GoalStatus(goals.get(g).text(), GoalStatus.State.OPEN, -1, null);
        }
        for (int n = 0; n < graph.size(); n++) {
            for (DiscreteGraph.Arc a : graph.arcs(n)) {
                if (a.channel() >= 0 && partition.observable(a.channel()) != Partition.INTERNAL) {
                    for (int e : a.edges()) {
                        coverable.set(e);
                        if (partition.isEnvironment(graph.processOf(e))) {
                            environmentEdges.set(e);
                        }
                    }
                }
            }
        }
        openChanged();
        if (steering.strategy() == Strategy.COVERAGE) {
            BitSet goalsOpen = new BitSet();
            for (int g = 0; g < status.length; g++) {
                if (status[g].state() == GoalStatus.State.OPEN) {
                    goalsOpen.set(g);
                }
            }
            cover = CoverTable.of(graph, coverable, goalsOpen, steering.horizon());
        }
    }

    /**
     * The steerer of a run of {@code network} on the tester's {@code semantics}.
     *
     * @throws io.dtron.engine.verify.QueryException when a goal is no {@code E<>} query or does not compile
     */
    public static Steerer of(Steering steering, Network network, Semantics semantics, Partition partition,
                             List<String> traps) {
        List<Query> goals = new ArrayList<>();
        List<StateProperty> properties = new ArrayList<>();
        List<String> texts = new ArrayList<>(steering.goals());
        for (String trap : traps) {
            texts.add("E<> " + trap);
        }
        for (String text : texts) {
            Query q = Query.parse(text);
            properties.add(StateProperty.goal(network, q, semantics.ticksPerUnit()));
            goals.add(q);
        }
        DiscreteGraph graph = DiscreteGraph.cached(network, goals, MAX_STATES);
        return new Steerer(steering, network, semantics, partition, graph, goals, properties,
                steering.goals().size());
    }

    /** How many goals there are. */
    public int goalCount() {
        return userGoals;
    }

    /** Whether goal {@code g} (from 0) is reached. */
    public boolean reached(int g) {
        return status[g].state() == GoalStatus.State.REACHED;
    }

    /** The goals and where they stand. */
    public List<GoalStatus> goals() {
        return List.of(status).subList(0, userGoals);
    }

    /** Whether the exploration before the run saw every reachable state (else unreachability is not proved). */
    public boolean complete() {
        return graph.complete();
    }

    /** How many edges coverage counts (on inputs and outputs, reachable), and how many of them are covered. */
    public int[] edgeCoverage() {
        BitSet c = (BitSet) covered.clone();
        c.and(coverable);
        return new int[] {c.cardinality(), coverable.cardinality()};
    }

    /** The environment's edges on inputs and outputs that are reachable, and how many of them are covered. */
    public int[] environmentCoverage() {
        BitSet c = (BitSet) covered.clone();
        c.and(environmentEdges);
        return new int[] {c.cardinality(), environmentEdges.cardinality()};
    }

    /** When all of {@link #environmentCoverage} was first covered (microseconds), and after how many inputs. */
    public long[] environmentCovered() {
        return new long[] {environmentCoveredMicros, environmentCoveredInputs};
    }

    // ------------------------------------------------------------------------------------------------ scoring

    /** The planner's scores of the moves the plan offers, for {@link Plan#choose}; null when nothing steers. */
    public Plan.Scorer scorer() {
        if (steering.strategy() == Strategy.RANDOM) {
            return null;
        }
        return new Plan.Scorer() {
            @Override
            public int input(SymState from, Semantics.Move move) {
                return score(from, move);
            }

            @Override
            public int waiting(List<SymState> reach) {
                return waitScore(reach);
            }

            @Override
            public long patience(List<SymState> reach) {
                return patienceTicks(reach);
            }
        };
    }

    long patienceTicks(List<SymState> reach) {
        if (limits == null) {
            return 100L * semantics.ticksPerUnit();
        }
        int[] lo = new int[semantics.dimension()];
        int[] up = new int[semantics.dimension()];
        long most = 0;
        for (SymState s : reach) {
            limits.fill(s, lo, up);
            for (int x = 1; x < lo.length; x++) {
                most = Math.max(most, Math.max(lo[x], up[x]));
            }
        }
        return (most + 1) * semantics.ticksPerUnit();
    }

    private int cap(int score) {
        if (steering.strategy() == Strategy.COVERAGE) {
            return score; // a sum, already bounded term by term
        }
        return score > steering.horizon() ? DiscreteGraph.UNREACHABLE : score;
    }

    int score(SymState from, Semantics.Move move) {
        int n = graph.node(from);
        if (n < 0) {
            return DiscreteGraph.UNREACHABLE;
        }
        int[] edges = graph.edgesOf(move);
        int best = DiscreteGraph.UNREACHABLE;
        for (DiscreteGraph.Arc a : graph.arcs(n)) {
            if (a.channel() == move.channel() && Arrays.equals(a.edges(), edges)) {
                best = Math.min(best, arcScore(a));
            }
        }
        return cap(best);
    }

    private int arcScore(DiscreteGraph.Arc a) {
        if (steering.strategy() == Strategy.COVERAGE) {
            return coverageScore(a);
        }
        int best = DiscreteGraph.UNREACHABLE;
        if (openDistance != null) {
            best = Math.min(best, 1 + openDistance[a.target()]);
        }
        return best;
    }

    /**
     * The coverage strategy's score of an arc: with few targets left (edges not covered, open goals and traps; see
     * {@link CoverTable}), one move plus the fewest moves from the arc's target that cover all of them together, each
     * one given up costing the horizon plus one; with more, the sum over the targets of the moves from the arc's
     * target to each (0 for an edge the arc covers), each counted at most to the horizon. Either way the move that
     * brings the most targets nearer, not only the nearest one; unreachable when no target is within the horizon.
     */
    private int coverageScore(DiscreteGraph.Arc a) {
        Integer known = arcScores.get(a);
        if (known != null) {
            return known;
        }
        int left = coverLeft();
        int score = left >= 0 ? cover.score(a, left) : sumOfDistances(a);
        arcScores.put(a, score);
        return score;
    }

    /**
     * The targets left as a mask of {@link #cover}; -1 when there is no table for them (too many before the run: the
     * sum of distances scores). The table is built before the run only, never in a step.
     */
    private int coverLeft() {
        if (coverLeft != -2) {
            return coverLeft;
        }
        BitSet edgesLeft = (BitSet) coverable.clone();
        edgesLeft.andNot(covered);
        BitSet goalsLeft = new BitSet();
        for (int g = 0; g < status.length; g++) {
            if (status[g].state() == GoalStatus.State.OPEN) {
                goalsLeft.set(g);
            }
        }
        coverLeft = cover == null ? -1 : cover.maskOf(edgesLeft, goalsLeft);
        return coverLeft;
    }

    /** The plan that covers the targets left together, when they are few enough; null else. */
    private CoverTable cover;
    /** The targets left as a mask of {@link #cover}; -1 without a table for them, -2 when to be worked out. */
    private int coverLeft = -2;

    private int sumOfDistances(DiscreteGraph.Arc a) {
        int h = steering.horizon();
        long sum = 0;
        boolean within = false;
        for (int e = coverable.nextSetBit(0); e >= 0; e = coverable.nextSetBit(e + 1)) {
            if (covered.get(e)) {
                continue;
            }
            int d = contains(a.edges(), e) ? 0 : 1 + edgeDistance(e)[a.target()];
            within |= d <= h;
            sum += Math.min(d, h + 1);
        }
        for (int g = 0; g < status.length; g++) {
            if (status[g].state() == GoalStatus.State.OPEN) {
                int d = 1 + goalDistance[g][a.target()];
                within |= d <= h;
                sum += Math.min(d, h + 1);
            }
        }
        return within ? (int) Math.min(sum, DiscreteGraph.UNREACHABLE - 1) : DiscreteGraph.UNREACHABLE;
    }

    private static boolean contains(int[] edges, int e) {
        for (int x : edges) {
            if (x == e) {
                return true;
            }
        }
        return false;
    }

    /** The coverage scores of the arcs while the targets stay the same. */
    private final Map<DiscreteGraph.Arc, Integer> arcScores = new java.util.IdentityHashMap<>();

    /** Per edge, the distance of every node to an arc that takes it; the graph does not change, so kept for good. */
    private final Map<Integer, int[]> edgeDistances = new HashMap<>();

    private int[] edgeDistance(int e) {
        return edgeDistances.computeIfAbsent(e, k -> graph.distances(new BitSet(), arc -> contains(arc.edges(), k)));
    }

    int waitScore(List<SymState> reach) {
        int best = DiscreteGraph.UNREACHABLE;
        BitSet seen = new BitSet();
        for (SymState s : reach) {
            int n = graph.node(s);
            if (n < 0 || seen.get(n)) {
                continue;
            }
            seen.set(n);
            if (openDistance != null && openDistance[n] == 0) {
                return 0; // a goal that holds here may need time to pass
            }
            for (DiscreteGraph.Arc a : graph.arcs(n)) {
                if (a.channel() < 0 || partition.observable(a.channel()) != Partition.INPUT) {
                    best = Math.min(best, arcScore(a));
                }
            }
        }
        return cap(best);
    }

    private void openChanged() {
        arcScores.clear();
        coverLeft = -2;
        int[] d = null;
        int targets = steering.strategy() == Strategy.COVERAGE ? status.length : userGoals;
        for (int g = 0; g < targets; g++) {
            if (status[g].state() == GoalStatus.State.OPEN) {
                if (d == null) {
                    d = goalDistance[g].clone();
                } else {
                    for (int n = 0; n < d.length; n++) {
                        d[n] = Math.min(d[n], goalDistance[g][n]);
                    }
                }
            }
        }
        openDistance = d;
    }

    // ------------------------------------------------------------------------------------------------ following

    /**
     * The moves {@code kept} (successors on one observable channel) were taken at {@code micros}, the {@code
     * inputs}-th input so far: counts their edges as covered (each edge of every one, as the system may have taken
     * any of them), the goals that held in every state they start from, and the system's choice among its outputs;
     * returns a stop when the fairness bound is passed.
     */
    public Stop taken(List<StateSet.Successor> kept, long micros, int inputs, boolean output) {
        passedThrough(kept, micros);
        boolean grew = false;
        for (StateSet.Successor s : kept) {
            for (int e : graph.edgesOf(s.move())) {
                if (!covered.get(e)) {
                    covered.set(e);
                    grew = true;
                }
            }
        }
        if (grew) {
            arcScores.clear();
            coverLeft = -2;
            if (environmentCoveredMicros < 0 && !environmentEdges.isEmpty()) {
                BitSet missing = (BitSet) environmentEdges.clone();
                missing.andNot(covered);
                if (missing.isEmpty()) {
                    environmentCoveredMicros = micros;
                    environmentCoveredInputs = inputs;
                }
            }
        }
        return output && steering.fairness() >= 0 ? fairness(kept) : null;
    }

    /**
     * Marks reached the open goals that hold in every state the moves {@code kept} start from: the system was in one
     * of them at {@code micros}, just before the event, even when it got there by internal moves after the last
     * event and leaves again by this one (a location entered and left between two observations).
     */
    private void passedThrough(List<StateSet.Successor> kept, long micros) {
        if (kept.isEmpty()) {
            return;
        }
        List<SymState> from = new ArrayList<>(kept.size());
        for (StateSet.Successor s : kept) {
            from.add(s.from());
        }
        boolean changed = false;
        for (int g = 0; g < status.length; g++) {
            if (status[g].state() == GoalStatus.State.OPEN && holdsInEvery(g, from)) {
                status[g] = new GoalStatus(status[g].text(), GoalStatus.State.REACHED, micros, null);
                changed = true;
            }
        }
        if (changed) {
            openChanged();
        }
    }

    /** Whether goal {@code g} holds in every one of {@code states}. */
    private boolean holdsInEvery(int g, List<SymState> states) {
        for (SymState s : states) {
            if (!properties.get(g).holdsSomewhere(s)) {
                return false;
            }
        }
        return true;
    }

    /**
     * Counts the system's choice of {@code kept} at its source, when it has one source node and several output
     * arcs; a stop when an arc that a target needs was starved by more than the fairness bound.
     */
    private Stop fairness(List<StateSet.Successor> kept) {
        int node = -1;
        int[] edges = null;
        for (StateSet.Successor s : kept) {
            int n = graph.node(s.from());
            int[] e = graph.edgesOf(s.move());
            if (node >= 0 && (n != node || !Arrays.equals(e, edges)) || n < 0) {
                return null; // not one choice the tester can name
            }
            node = n;
            edges = e;
        }
        if (node < 0) {
            return null;
        }
        DiscreteGraph.Arc[] arcs = graph.arcs(node);
        List<Integer> alternatives = new ArrayList<>();
        int taken = -1;
        for (int i = 0; i < arcs.length; i++) {
            if (arcs[i].channel() >= 0 && partition.observable(arcs[i].channel()) == Partition.OUTPUT) {
                alternatives.add(i);
                if (Arrays.equals(arcs[i].edges(), edges)) {
                    taken = i;
                }
            }
        }
        if (taken < 0 || alternatives.size() < 2) {
            return null;
        }
        int[] counts = choices.computeIfAbsent(node, k -> new int[arcs.length]);
        counts[taken]++;
        int most = Arrays.stream(counts).max().orElse(0);
        int takenScore = arcScore(arcs[taken]);
        for (int i : alternatives) {
            if (most - counts[i] > steering.fairness() && cap(arcScore(arcs[i])) < takenScore) {
                StringBuilder counted = new StringBuilder();
                for (int j : alternatives) {
                    counted.append(counted.length() == 0 ? "" : ", ").append(describe(arcs[j])).append(' ')
                            .append(counts[j]).append(counts[j] == 1 ? " time" : " times");
                }
                return new Stop(Verdict.INCONCLUSIVE, "the system's choice in " + semantics.describe(
                        kept.get(0).from(), null) + " is not " + steering.fairness() + "-fair: " + counted
                        + "; " + describe(arcs[i]) + " is starved and " + needs() + " needs it (--fairness "
                        + steering.fairness() + ")");
            }
        }
        return null;
    }

    private String needs() {
        for (int g = 0; g < status.length; g++) {
            if (status[g].state() == GoalStatus.State.OPEN) {
                return (g < userGoals ? "goal '" : "trap '") + status[g].text().substring(g < userGoals ? 0 : 4)
                        + "'";
            }
        }
        return "the coverage of the model";
    }

    /** An arc as people read it: its channel and edges. */
    private String describe(DiscreteGraph.Arc a) {
        StringBuilder sb = new StringBuilder(a.channel() >= 0 ? network.channelName(a.channel()) + " (" : "(");
        for (int i = 0; i < a.edges().length; i++) {
            int e = a.edges()[i];
            Process p = network.processes().get(graph.processOf(e));
            io.dtron.model.Edge edge = p.edges().get(e - graph.edge(p.index(), 0));
            sb.append(i == 0 ? "" : ", ").append(p.name()).append(": ").append(p.locations().get(edge.source())
                    .name()).append(" -> ").append(p.locations().get(edge.target()).name());
        }
        return sb.append(')').toString();
    }

    /**
     * Looks at the goals in {@code set} (the states the system may be in at {@code micros}): an open goal that holds
     * in every one is reached, one that no path leads to from any of them is unreachable. Returns a stop when every
     * goal is reached or unreachable (and the steering stops when done), else null.
     */
    public Stop check(StateSet set, long micros, String after) {
        if (status.length == 0 || set.isEmpty()) {
            return null;
        }
        boolean changed = false;
        for (int g = 0; g < status.length; g++) {
            if (status[g].state() != GoalStatus.State.OPEN) {
                continue;
            }
            if (holdsInEvery(g, set.states())) {
                status[g] = new GoalStatus(status[g].text(), GoalStatus.State.REACHED, micros, null);
                changed = true;
                continue;
            }
            if (graph.complete() && unreachableFrom(set, g)) {
                boolean[] implementation = new boolean[network.processes().size()];
                for (int p = 0; p < implementation.length; p++) {
                    implementation[p] = !partition.isEnvironment(p);
                }
                status[g] = new GoalStatus(status[g].text(), GoalStatus.State.UNREACHABLE, micros,
                        after + " the implementation is in " + semantics.describe(set.states().get(0),
                                implementation) + ", and no path of the model leads from there to the goal");
                changed = true;
            }
        }
        if (changed) {
            openChanged();
        }
        return stopWhenDone();
    }

    /**
     * The stop when every goal is done (also before the run): INCONCLUSIVE when one is unreachable, PASSED when all
     * were reached and the steering stops then (not under a stop condition, which decides itself); else null.
     */
    public Stop stopWhenDone() {
        if (userGoals == 0) {
            return null;
        }
        StringBuilder reached = new StringBuilder();
        StringBuilder unreachable = new StringBuilder();
        for (GoalStatus s : goals()) {
            if (s.state() == GoalStatus.State.OPEN) {
                return null;
            }
            StringBuilder to = s.state() == GoalStatus.State.REACHED ? reached : unreachable;
            to.append(to.length() == 0 ? "" : "; ").append('\'').append(s.text()).append('\'')
                    .append(s.state() == GoalStatus.State.UNREACHABLE ? ": " + s.reason() : "");
        }
        if (unreachable.length() == 0) {
            return steering.stopWhenDone() ? new Stop(Verdict.PASSED, "every goal was reached: " + reached) : null;
        }
        return new Stop(Verdict.INCONCLUSIVE, "a goal can no longer be reached, so the run cannot serve its"
                + " purpose: " + unreachable + (reached.length() > 0 ? " (reached: " + reached + ")" : ""));
    }

    /**
     * The goals still open at the end of a run, quoted and joined ({@code 'E<> p'; 'E<> q'}), when the goals decide
     * when the run has done enough (no stop condition): the run did not serve its purpose. Empty when every goal was
     * reached or found unreachable, or when a stop condition decides.
     */
    public String openAtTheEnd() {
        StringBuilder open = new StringBuilder();
        for (GoalStatus s : steering.stopWhenDone() ? goals() : List.<GoalStatus>of()) {
            if (s.state() == GoalStatus.State.OPEN) {
                open.append(open.length() == 0 ? "" : "; ").append('\'').append(s.text()).append('\'');
            }
        }
        return open.toString();
    }

    private boolean unreachableFrom(StateSet set, int g) {
        for (SymState s : set.states()) {
            int n = graph.node(s);
            if (n < 0 || goalDistance[g][n] < DiscreteGraph.UNREACHABLE) {
                return false;
            }
        }
        return true;
    }

    /** Whether a goal mentions clocks: then it is looked at while time passes too, not only at events. */
    public boolean goalsDependOnTime() {
        for (int g = 0; g < status.length; g++) {
            if (status[g].state() == GoalStatus.State.OPEN && properties.get(g).dependsOnZone()) {
                return true;
            }
        }
        return false;
    }
}
