package io.dtron.engine.internal.tester;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.Steering;
import io.dtron.engine.Strategy;
import java.util.Arrays;
import java.util.List;
import java.util.Random;

/**
 * The cost of one step of the coverage strategy, as a plain main (not a timed test): on the state sets of {@link
 * StateSetBenchmark}'s recorded runs (LightContr, and the eight nondeterministic timers), the plan of the next step
 * ({@link Plan#of}), the steered choice ({@link Plan#choose} with the coverage scorer) and the goal check, each step
 * timed alone, many rounds; prints p50, p99 and the maximum per model, with the unsteered step (plan and random
 * choice) beside it. The exploration before the run is timed once, and apart from it the steerer's making (the coverage
 * strategy's table of moves that cover the targets together, when there are few enough). Run by {@code scripts/coverage-bench.sh}.
 */
public final class SteeringBench {
    private static final int TICKS = 1000;

    private SteeringBench() {
    }

    public static void main(String[] args) throws Exception {
        int rounds = args.length > 0 ? Integer.parseInt(args[0]) : 200;
        for (String model : List.of("lightcontr", "timers")) {
            StateSetBenchmark recorded = new StateSetBenchmark();
            recorded.model = model;
            recorded.record();
            List<StateSet> sets = recorded.recordedSets();
            long t0 = System.nanoTime();
            io.dtron.engine.internal.verify.DiscreteGraph.cached(recorded.semantics().network(), List.of(),
                    Steerer.MAX_STATES);
            long explore = System.nanoTime() - t0;
            t0 = System.nanoTime();
            // the exploration is cached: this builds the table of moves that cover the targets together, if any
            Steerer steerer = Steerer.of(new Steering(Strategy.COVERAGE, List.of(), Steering.DEFAULT_HORIZON, -1,
                    false), recorded.semantics().network(), recorded.semantics(), recorded.partition(), List.of());
            long table = System.nanoTime() - t0;
            long[] steered = time(recorded, sets, steerer, rounds);
            long[] plain = time(recorded, sets, null, rounds);
            System.out.printf("%s: %d steps x %d rounds; exploration before the run %.1f ms, then the steerer (its"
                            + " cover table, if any) %.1f ms; coverage step p50 %.1f us,"
                            + " p99 %.1f us, max %.1f us; unsteered step p50 %.1f us, p99 %.1f us, max %.1f us%n",
                    model, sets.size(), rounds, explore / 1e6, table / 1e6, pct(steered, 50), pct(steered, 99),
                    steered[steered.length - 1] / 1e3, pct(plain, 50), pct(plain, 99), plain[plain.length - 1] / 1e3);
        }
    }

    private static long[] time(StateSetBenchmark recorded, List<StateSet> sets, Steerer steerer, int rounds) {
        Random random = new Random(1);
        Plan.Scorer scorer = steerer == null ? null : steerer.scorer();
        long[] out = new long[sets.size() * rounds];
        int i = 0;
        long sink = 0;
        for (int r = 0; r < rounds; r++) {
            for (StateSet set : sets) {
                long t = System.nanoTime();
                if (steerer != null) {
                    steerer.check(set, 0, "");
                }
                Plan plan = Plan.of(set, recorded.semantics(), recorded.partition(), recorded.testInterface(), 1000,
                        100_000L * TICKS);
                Plan.Choice c = plan.choose(0, random, DelayPolicy.RANDOM, 0, 0, ch -> 0, 0, scorer);
                out[i++] = System.nanoTime() - t;
                sink += c.ticks();
            }
        }
        if (sink == 42) {
            System.out.print("");
        }
        Arrays.sort(out);
        return out;
    }

    private static double pct(long[] sorted, int p) {
        return sorted[Math.min(sorted.length - 1, (int) Math.ceil(sorted.length * p / 100.0) - 1)] / 1e3;
    }
}
