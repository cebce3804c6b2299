package io.dtron.engine.sim;

import io.dtron.engine.OnlineTester;
import io.dtron.engine.Steering;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.Verdict;
import io.dtron.engine.internal.eval.ModelRuntimeException;
import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.PartitionException;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sim.Mutator;
import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import io.dtron.engine.verify.VerificationResult;
import io.dtron.engine.verify.Verifier;
import io.dtron.engine.verify.VerifierOptions;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;

/**
 * Mutation analysis of a model's implementation part: {@link #derive} makes the mutants, {@link #run} runs the
 * tester, with the model as specification, against each mutant as the system under test ({@link ModelSystem}) in
 * virtual time, for a budget of time units and a number of seeds, and says which were killed (a run FAILED).
 */
public final class Mutants {
    private Mutants() {
    }

    /**
     * The mutants of the implementation part of {@code network} (split by {@code testInterface}). A mutant the
     * engine refuses is {@link Mutant#invalid() invalid}; one whose change takes effect only at a location the
     * checker proves unreachable in the closed network (an edge's source, an invariant's or urgent location) is
     * {@link Mutant#equivalent() equivalent}. The checker's search for each location is bounded by {@code
     * checkTime}; a search that stops at the bound proves nothing.
     *
     * @throws UnsupportedModelException when the interface does not split the model, or the engine cannot run it
     */
    public static List<Mutant> derive(Network network, TestInterface testInterface, Duration checkTime) {
        Partition partition;
        try {
            partition = Partition.of(network, testInterface);
        } catch (PartitionException e) {
            throw new UnsupportedModelException(e.getMessage());
        }
        new Semantics(network, 1);
        boolean[] inside = new boolean[network.processes().size()];
        for (int p = 0; p < inside.length; p++) {
            inside[p] = !partition.isEnvironment(p);
        }
        Verifier verifier = new Verifier(network, VerifierOptions.defaults().withTimeLimit(checkTime));
        Map<String, String> unreachable = new HashMap<>();
        List<Mutant> out = new ArrayList<>();
        for (Mutator.Change c : Mutator.changes(network, inside, testInterface)) {
            String where = c.pos().fragment().file() + ":" + c.pos().line();
            String invalid = invalid(c.network());
            String place = c.process().name() + "." + c.location().name();
            String equivalent = invalid != null ? null
                    : unreachable.computeIfAbsent(place, q -> unreachable(verifier, place));
            out.add(new Mutant(out.size() + 1, c.kind(), c.process().name(), c.change(), where,
                    invalid == null ? c.network() : null, invalid, equivalent == null || equivalent.isEmpty() ? null
                    : equivalent));
        }
        return out;
    }

    /** Why the engine refuses {@code mutant}, or null. */
    private static String invalid(Network mutant) {
        try {
            new Semantics(mutant, 1).initial();
            return null;
        } catch (UnsupportedModelException | ModelRuntimeException | IllegalArgumentException e) {
            return e.getMessage();
        }
    }

    /** Why {@code place} is unreachable, or "" when it is reachable or the checker cannot say. */
    private static String unreachable(Verifier verifier, String place) {
        try {
            VerificationResult r = verifier.verify(Query.parse("E<> " + place));
            return r.outcome() == VerificationResult.Outcome.VIOLATED ? place + " is unreachable (E<> " + place
                    + " does not hold)" : "";
        } catch (QueryException | UnsupportedModelException e) {
            return "";
        }
    }

    /**
     * Runs the tester against each mutant that is neither invalid nor equivalent, with {@code options} (its seed
     * the first of {@code seeds} consecutive seeds, its timeout the budget in time units, virtual time), until a
     * run FAILS or the seeds are used up, on {@code threads} threads; and the model itself as system with the same
     * seeds, which must PASS. A mutant whose run meets a model error is invalid.
     */
    public static MutationReport run(Network network, TestInterface testInterface, List<Mutant> mutants,
                                     TestOptions options, int seeds, int threads) {
        return run(network, testInterface, mutants, options, null, seeds, threads);
    }

    /**
     * {@link #run(Network, TestInterface, List, TestOptions, int, int) Runs} the tester against each mutant, every run
     * steered by {@code steering} (null: none) as {@link OnlineTester#steer} steers a run. The planner's exploration
     * of the model is done once and shared by every run: the tester's model is the unmutated one, whatever the mutant,
     * so the exploration is the same for all.
     *
     * @throws io.dtron.engine.verify.QueryException when a goal of {@code steering} is not an {@code E<>} query or
     *                                               does not compile
     */
    public static MutationReport run(Network network, TestInterface testInterface, List<Mutant> mutants,
                                     TestOptions options, Steering steering, int seeds, int threads) {
        if (seeds < 1 || threads < 1) {
            throw new IllegalArgumentException("seeds and threads must be at least 1");
        }
        List<Long> seedList = new ArrayList<>();
        for (int i = 0; i < seeds; i++) {
            seedList.add(options.seed() + i);
        }
        TestOptions base = options.withVirtualTime(true);
        long start = System.nanoTime();
        if (steering != null) {
            // explores the model for the planner before the runs share it, and refuses goals that do not compile
            new OnlineTester(network, testInterface, new ModelSystem(network, testInterface, 0), base).steer(steering);
        }
        ExecutorService pool = Executors.newFixedThreadPool(threads, r -> {
            Thread t = new Thread(r, "dtron-mutants");
            t.setDaemon(true);
            return t;
        });
        try {
            Future<String[]> model = pool.submit(() -> modelRuns(network, testInterface, base, steering, seedList));
            List<Future<MutationReport.Outcome>> futures = new ArrayList<>();
            for (Mutant m : mutants) {
                futures.add(pool.submit(() -> outcome(network, testInterface, m, base, steering, seedList)));
            }
            List<MutationReport.Outcome> outcomes = new ArrayList<>();
            for (Future<MutationReport.Outcome> f : futures) {
                outcomes.add(f.get());
            }
            String[] modelResult = model.get();
            return new MutationReport(outcomes, seedList, options.timeout(), Integer.parseInt(modelResult[0]),
                    modelResult[1], System.nanoTime() - start);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IllegalStateException("interrupted", e);
        } catch (ExecutionException e) {
            throw e.getCause() instanceof RuntimeException r ? r : new IllegalStateException(e.getCause());
        } finally {
            pool.shutdownNow();
        }
    }

    private static String[] modelRuns(Network network, TestInterface testInterface, TestOptions base,
                                      Steering steering, List<Long> seeds) {
        int passed = 0;
        String problem = null;
        for (long seed : seeds) {
            TestResult r = once(network, network, testInterface, base, steering, seed);
            if (r.verdict() == Verdict.PASSED) {
                passed++;
            } else if (problem == null) {
                problem = "seed " + seed + ": " + r.verdict() + ": " + r.explanation();
            }
        }
        return new String[] {String.valueOf(passed), problem};
    }

    private static MutationReport.Outcome outcome(Network network, TestInterface testInterface, Mutant m,
                                                  TestOptions base, Steering steering, List<Long> seeds) {
        if (m.invalid() != null) {
            return new MutationReport.Outcome(m, MutationReport.Status.INVALID, 0, m.invalid());
        }
        if (m.equivalent() != null) {
            return new MutationReport.Outcome(m, MutationReport.Status.EQUIVALENT, 0, m.equivalent());
        }
        int inconclusive = 0;
        String firstInconclusive = null;
        for (long seed : seeds) {
            TestResult r;
            try {
                r = once(network, m.network(), testInterface, base, steering, seed);
            } catch (ModelRuntimeException | UnsupportedModelException e) {
                return new MutationReport.Outcome(m, MutationReport.Status.INVALID, seed, e.getMessage());
            }
            if (r.verdict() == Verdict.FAILED) {
                return new MutationReport.Outcome(m, MutationReport.Status.KILLED, seed, r.explanation());
            }
            if (r.verdict() == Verdict.INCONCLUSIVE) {
                if (r.explanation().contains(ModelSystem.MODEL_ERROR)) {
                    return new MutationReport.Outcome(m, MutationReport.Status.INVALID, seed, r.explanation());
                }
                inconclusive++;
                if (firstInconclusive == null) {
                    firstInconclusive = "seed " + seed + ": " + r.explanation();
                }
            }
        }
        return new MutationReport.Outcome(m, MutationReport.Status.SURVIVED, 0, inconclusive == 0
                ? "every run PASSED" : inconclusive + " of " + seeds.size() + " runs INCONCLUSIVE, first " + firstInconclusive);
    }

    /** One run of the tester with {@code spec} against {@code system} as the system under test. */
    private static TestResult once(Network spec, Network system, TestInterface testInterface, TestOptions base,
                                   Steering steering, long seed) {
        TestOptions options = new TestOptions(seed, base.timeUnitMicros(), base.timeout(), base.delayPolicy(),
                base.delayBound(), true, base.reorderWindowMicros(), base.inputMarginMicros(), base.shortDelayBound());
        OnlineTester tester = new OnlineTester(spec, testInterface, new ModelSystem(system, testInterface,
                ModelSystem.seedFor(seed)), options);
        if (steering != null) {
            tester.steer(steering);
        }
        return tester.run();
    }
}
