package io.dtron.engine.sim;

import java.util.List;

/**
 * What running the tester against each mutant found.
 *
 * @param outcomes  one per mutant, in the mutants' order
 * @param seeds     the run seeds tried against each mutant (the first is the base seed)
 * @param budget    the time units of each run
 * @param modelRuns the model itself as system against the same seeds: how many runs PASSED (all, for a correct
 *                  engine), and the first other verdict with its explanation, or null
 * @param wallNanos the wall time of the mutants' runs
 */
public record MutationReport(List<Outcome> outcomes, List<Long> seeds, long budget, int modelRuns, String modelProblem,
                             long wallNanos) {
    public MutationReport {
        outcomes = List.copyOf(outcomes);
        seeds = List.copyOf(seeds);
    }

    /** What became of a mutant. */
    public enum Status { KILLED, SURVIVED, EQUIVALENT, INVALID }

    /**
     * One mutant's fate.
     *
     * @param mutant      the mutant
     * @param status      killed (a run FAILED), survived, equivalent (proved, not run) or invalid (not counted)
     * @param seed        the seed of the run that killed it, or 0
     * @param explanation the killing run's explanation, why it is equivalent or invalid, or how the runs ended
     */
    public record Outcome(Mutant mutant, Status status, long seed, String explanation) {
    }

    /** How many mutants have {@code status}. */
    public long count(Status status) {
        return outcomes.stream().filter(o -> o.status() == status).count();
    }

    /** The mutants that count: killed plus survived (equivalent and invalid ones are left out). */
    public long total() {
        return count(Status.KILLED) + count(Status.SURVIVED);
    }

    /**
     * The runs of the tester: those against the mutants (a killed mutant's up to its killing seed, a survivor's one
     * per seed) and the model's own, one per seed.
     */
    public long runs() {
        long runs = seeds.size();
        for (Outcome o : outcomes) {
            runs += switch (o.status()) {
                case KILLED -> seeds.indexOf(o.seed()) + 1;
                case SURVIVED -> seeds.size();
                case INVALID -> o.seed() == 0 ? 0 : seeds.indexOf(o.seed()) + 1;
                case EQUIVALENT -> 0;
            };
        }
        return runs;
    }

    /** Killed over {@link #total()}, 1 when there is nothing to kill. */
    public double score() {
        return total() == 0 ? 1 : (double) count(Status.KILLED) / total();
    }
}
