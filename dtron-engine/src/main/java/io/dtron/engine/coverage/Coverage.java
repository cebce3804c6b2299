package io.dtron.engine.coverage;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;

/**
 * What one run, or a suite of runs {@linkplain #union merged}, covered of a model: each process's locations and
 * edges (environment and implementation), the traps, and the observable channels with the values their attached
 * variables carried. Figures are measured against what can be covered: what the model checker proved unreachable
 * in the closed network is left out of the denominator and listed by {@link #unreachable()}; when its check ran out
 * of budget, {@link #reachabilityNote()} says so and the elements it could not decide count as coverable.
 * Immutable.
 *
 * @param model            the model file
 * @param fingerprint      a digest of the model's processes, locations and edges: runs of the same model have the
 *                         same one, and only those can be merged
 * @param seeds            the seeds of the runs counted
 * @param processes        each process's locations and edges, in the order of the system line
 * @param traps            the traps, in state-vector order
 * @param channels         the observable channels, inputs then outputs, in interface order
 * @param reachabilityNote null when the check of what can be covered was complete; else why it was not (its
 *                         budget ran out), and the undecided elements count as coverable
 */
public record Coverage(String model, String fingerprint, List<Long> seeds, List<ProcessCoverage> processes,
                       List<Trap> traps, List<ChannelCoverage> channels, String reachabilityNote) {

    public Coverage {
        Objects.requireNonNull(model, "model");
        Objects.requireNonNull(fingerprint, "fingerprint");
        seeds = List.copyOf(seeds);
        processes = List.copyOf(processes);
        traps = List.copyOf(traps);
        channels = List.copyOf(channels);
    }

    /** The {@link #fingerprint} of the runs of {@code network}: a digest of its processes, locations and edges. */
    public static String fingerprintOf(io.dtron.model.Network network) {
        return io.dtron.engine.internal.coverage.Recorder.fingerprint(network);
    }

    /** The most unreachable elements the summary names; the coverage file lists them all. */
    public static final int SUMMARY_UNREACHABLE = 5;

    /** How far an element was covered: not, by some of the possible states only, or for certain. */
    public enum Taken {
        NO, POSSIBLY, CERTAINLY;

        /** The more covered of the two. */
        public Taken max(Taken o) {
            return compareTo(o) >= 0 ? this : o;
        }
    }

    /** What the model checker says of an element: reachable, proved unreachable, or undecided (budget). */
    public enum Reach {
        REACHABLE, UNREACHABLE, UNKNOWN;

        /** What two checks together know: a proof of either kind wins over an undecided one. */
        public Reach and(Reach o) {
            return this == UNKNOWN ? o : this;
        }

        /** Whether the element counts in the denominator. */
        public boolean coverable() {
            return this != UNREACHABLE;
        }
    }

    /**
     * A process's coverage.
     *
     * @param name        the process ({@code Lamp}, {@code Train(2)})
     * @param template    its template
     * @param environment whether it is part of the environment (else of the implementation under test)
     * @param locations   its locations by index
     * @param edges       its edges by index
     */
    public record ProcessCoverage(String name, String template, boolean environment, List<LocationCoverage> locations,
                                  List<EdgeCoverage> edges) {
        public ProcessCoverage {
            locations = List.copyOf(locations);
            edges = List.copyOf(edges);
        }
    }

    /**
     * A location.
     *
     * @param name  its name
     * @param line  the line it was declared on in the model file (0 when unknown)
     * @param reach what the model checker says of it
     * @param taken whether it was visited
     */
    public record LocationCoverage(String name, int line, Reach reach, Taken taken) {
    }

    /**
     * An edge.
     *
     * @param index  its number within the process
     * @param source its source location's name
     * @param target its target location's name
     * @param label  its synchronisation ({@code press?}), or empty
     * @param line   the line it was declared on in the model file (0 when unknown)
     * @param reach  what the model checker says of it
     * @param taken  whether it was taken
     */
    public record EdgeCoverage(int index, String source, String target, String label, int line, Reach reach,
                               Taken taken) {
        /** {@code source -> target}, with the label when there is one. */
        public String describe() {
            return source + " -> " + target + (label.isEmpty() ? "" : " " + label);
        }
    }

    /**
     * A trap: a boolean variable (or array element) the model sets on the edges a test must cover.
     *
     * @param name its name, {@code t[2]}
     * @param set  whether it was set
     */
    public record Trap(String name, Taken set) {
    }

    /**
     * An observable channel.
     *
     * @param name       its interface name
     * @param input      whether it is an input (else an output)
     * @param count      how many times it was observed
     * @param values     the distinct values of its attached variables, in the order first seen, at most {@link
     *                   #MAX_VALUES}
     * @param moreValues whether more distinct values were seen than are listed
     */
    public record ChannelCoverage(String name, boolean input, long count, List<Map<String, Integer>> values,
                                  boolean moreValues) {
        /** The most distinct values kept per channel. */
        public static final int MAX_VALUES = 50;

        public ChannelCoverage {
            List<Map<String, Integer>> copy = new ArrayList<>();
            for (Map<String, Integer> v : values) {
                copy.add(java.util.Collections.unmodifiableMap(new LinkedHashMap<>(v)));
            }
            values = List.copyOf(copy);
        }
    }

    /**
     * Covered out of coverable.
     *
     * @param covered  how many were covered for certain
     * @param total    how many can be covered
     */
    public record Figure(int covered, int total) {
        /** The percentage, 100 when there is nothing to cover. */
        public double percent() {
            return total == 0 ? 100.0 : 100.0 * covered / total;
        }

        /** {@code 7/8 (87.5%)}. */
        @Override
        public String toString() {
            return covered + "/" + total + " (" + String.format(java.util.Locale.ROOT, "%.1f", percent()) + "%)";
        }
    }

    /** Locations visited for certain, of the coverable ones. */
    public Figure locations() {
        int covered = 0;
        int total = 0;
        for (ProcessCoverage p : processes) {
            for (LocationCoverage l : p.locations()) {
                if (l.reach().coverable()) {
                    total++;
                    covered += l.taken() == Taken.CERTAINLY ? 1 : 0;
                }
            }
        }
        return new Figure(covered, total);
    }

    /** Edges taken for certain, of the coverable ones, environment and implementation. */
    public Figure edges() {
        return edges(null);
    }

    /** Edges of the environment ({@code true}) or of the implementation ({@code false}) taken for certain. */
    public Figure edges(Boolean environment) {
        int covered = 0;
        int total = 0;
        for (ProcessCoverage p : processes) {
            if (environment != null && p.environment() != environment) {
                continue;
            }
            for (EdgeCoverage e : p.edges()) {
                if (e.reach().coverable()) {
                    total++;
                    covered += e.taken() == Taken.CERTAINLY ? 1 : 0;
                }
            }
        }
        return new Figure(covered, total);
    }

    /** How many coverable edges were taken possibly but not for certain. */
    public int edgesPossiblyTaken() {
        int n = 0;
        for (ProcessCoverage p : processes) {
            for (EdgeCoverage e : p.edges()) {
                n += e.reach().coverable() && e.taken() == Taken.POSSIBLY ? 1 : 0;
            }
        }
        return n;
    }

    /** Traps set for certain, of all traps. */
    public Figure trapFigure() {
        int set = 0;
        for (Trap t : traps) {
            set += t.set() == Taken.CERTAINLY ? 1 : 0;
        }
        return new Figure(set, traps.size());
    }

    /**
     * What the model checker proved unreachable, by name: {@code Lamp.dead} for a location, {@code Lamp: off ->
     * dead (line 14)} for an edge.
     */
    public List<String> unreachable() {
        List<String> out = new ArrayList<>();
        for (ProcessCoverage p : processes) {
            for (LocationCoverage l : p.locations()) {
                if (l.reach() == Reach.UNREACHABLE) {
                    out.add(p.name() + "." + l.name() + (l.line() > 0 ? " (line " + l.line() + ")" : ""));
                }
            }
            for (EdgeCoverage e : p.edges()) {
                if (e.reach() == Reach.UNREACHABLE) {
                    out.add(p.name() + ": " + e.describe() + (e.line() > 0 ? " (line " + e.line() + ")" : ""));
                }
            }
        }
        return out;
    }

    /**
     * The summary line: {@code coverage: locations 7/8 (87.5%), edges 10/12 (83.3%) of reachable (environment 4/4
     * (100.0%), implementation 6/8 (75.0%), 1 more possibly); unreachable: Lamp.dead (line 9); traps 2/3 (66.7%)}. It names at most {@link #SUMMARY_UNREACHABLE} unreachable elements, then
     * says how many more there are.
     */
    public String summary() {
        StringBuilder sb = new StringBuilder("coverage: locations ").append(locations()).append(", edges ")
                .append(edges()).append(" of ").append(reachabilityNote == null ? "reachable" : "coverable")
                .append(" (environment ").append(edges(true)).append(", implementation ").append(edges(false));
        int possibly = edgesPossiblyTaken();
        if (possibly > 0) {
            sb.append(", ").append(possibly).append(" more possibly");
        }
        sb.append(')');
        List<String> unreachable = unreachable();
        if (!unreachable.isEmpty()) {
            sb.append("; unreachable: ").append(String.join(", ", unreachable.subList(0,
                    Math.min(unreachable.size(), SUMMARY_UNREACHABLE))));
            if (unreachable.size() > SUMMARY_UNREACHABLE) {
                sb.append(" and ").append(unreachable.size() - SUMMARY_UNREACHABLE).append(" more");
            }
        }
        if (reachabilityNote != null) {
            sb.append("; ").append(reachabilityNote);
        }
        if (!traps.isEmpty()) {
            sb.append("; traps ").append(trapFigure());
        }
        if (seeds.size() > 1) {
            sb.append("; ").append(seeds.size()).append(" runs");
        }
        return sb.toString();
    }

    /**
     * The coverage of a suite: everything any of the runs covered, each element at the most any run covered it,
     * channel counts added up.
     *
     * @throws IllegalArgumentException when the coverages are of different models (their fingerprints differ),
     *                                  naming the first that differs, or the list is empty
     */
    public static Coverage union(List<Coverage> runs) {
        if (runs.isEmpty()) {
            throw new IllegalArgumentException("no coverage to merge");
        }
        Coverage first = runs.get(0);
        for (Coverage c : runs) {
            if (!c.fingerprint().equals(first.fingerprint()) || !sameShape(c, first)) {
                throw new IllegalArgumentException("the coverage of " + c.model() + " is of a different model than"
                        + " that of " + first.model() + " (fingerprint " + c.fingerprint() + ", not "
                        + first.fingerprint() + ")");
            }
        }
        List<Long> seeds = new ArrayList<>();
        for (Coverage c : runs) {
            seeds.addAll(c.seeds());
        }
        List<ProcessCoverage> processes = new ArrayList<>();
        for (int p = 0; p < first.processes().size(); p++) {
            ProcessCoverage base = first.processes().get(p);
            List<LocationCoverage> locations = new ArrayList<>(base.locations());
            List<EdgeCoverage> edges = new ArrayList<>(base.edges());
            for (Coverage c : runs.subList(1, runs.size())) {
                ProcessCoverage o = c.processes().get(p);
                for (int l = 0; l < locations.size(); l++) {
                    LocationCoverage a = locations.get(l);
                    LocationCoverage b = o.locations().get(l);
                    locations.set(l, new LocationCoverage(a.name(), a.line(), a.reach().and(b.reach()),
                            a.taken().max(b.taken())));
                }
                for (int e = 0; e < edges.size(); e++) {
                    EdgeCoverage a = edges.get(e);
                    EdgeCoverage b = o.edges().get(e);
                    edges.set(e, new EdgeCoverage(a.index(), a.source(), a.target(), a.label(), a.line(),
                            a.reach().and(b.reach()), a.taken().max(b.taken())));
                }
            }
            processes.add(new ProcessCoverage(base.name(), base.template(), base.environment(), locations, edges));
        }
        Map<String, Taken> traps = new LinkedHashMap<>();
        Map<String, ChannelCoverage> channels = new LinkedHashMap<>();
        String note = null;
        boolean complete = false;
        for (Coverage c : runs) {
            for (Trap t : c.traps()) {
                traps.merge(t.name(), t.set(), Taken::max);
            }
            for (ChannelCoverage ch : c.channels()) {
                channels.merge(ch.name(), ch, Coverage::mergeChannel);
            }
            complete |= c.reachabilityNote() == null;
            note = note == null ? c.reachabilityNote() : note;
        }
        List<Trap> trapList = new ArrayList<>();
        traps.forEach((name, set) -> trapList.add(new Trap(name, set)));
        return new Coverage(first.model(), first.fingerprint(), seeds, processes, trapList,
                new ArrayList<>(channels.values()), complete ? null : note);
    }

    /** Whether {@code a} and {@code b} have as many processes, and each as many locations and edges. */
    private static boolean sameShape(Coverage a, Coverage b) {
        if (a.processes().size() != b.processes().size()) {
            return false;
        }
        for (int p = 0; p < a.processes().size(); p++) {
            ProcessCoverage x = a.processes().get(p);
            ProcessCoverage y = b.processes().get(p);
            if (x.locations().size() != y.locations().size() || x.edges().size() != y.edges().size()) {
                return false;
            }
        }
        return true;
    }

    private static ChannelCoverage mergeChannel(ChannelCoverage a, ChannelCoverage b) {
        Set<Map<String, Integer>> values = new LinkedHashSet<>(a.values());
        boolean more = a.moreValues() || b.moreValues();
        for (Map<String, Integer> v : b.values()) {
            if (values.size() < ChannelCoverage.MAX_VALUES) {
                values.add(v);
            } else if (!values.contains(v)) {
                more = true;
            }
        }
        return new ChannelCoverage(a.name(), a.input(), a.count() + b.count(), new ArrayList<>(values), more);
    }
}
