package io.dtron.models.streetlight;

import io.dtron.engine.Adapter;
import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.Steering;
import io.dtron.engine.SteeringReport;
import io.dtron.engine.Strategy;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.models.lamp.SmartLamp;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.function.Supplier;

/**
 * Coverage against random, as a plain main: on LightContr with the bundled smart lamp and on the street-light model
 * (two operators) with its in-process system of result codes, in virtual time, 20 seeds per strategy, the time
 * units and the inputs until every reachable edge of the environment on an input or output is covered. Prints, per
 * model and strategy, the median and the slowest seed, and how many seeds did not get there within the budget.
 * Run by {@code scripts/coverage-bench.sh}.
 */
public final class CoverageBench {
    private CoverageBench() {
    }

    /** One benchmark model: its network, interface, system under test and options. */
    private record Bench(String name, Network network, TestInterface iface, Supplier<Adapter> system,
                         TestOptions options) {
    }

    /** A strategy with a delay policy: dtron run's default, random with eager or bounded delays, coverage. */
    private record Variant(String name, Strategy strategy, DelayPolicy policy, long bound) {
    }

    private static final List<Variant> VARIANTS = List.of(
            new Variant("random (the default delay policy)", Strategy.RANDOM, DelayPolicy.RANDOM, 0),
            new Variant("random, --delay-policy eager", Strategy.RANDOM, DelayPolicy.EAGER, 0),
            new Variant("random, --delay-policy random-bounded --delay-bound 4", Strategy.RANDOM,
                    DelayPolicy.RANDOM_BOUNDED, 4),
            new Variant("coverage", Strategy.COVERAGE, DelayPolicy.RANDOM, 0));

    public static void main(String[] args) throws Exception {
        int seeds = args.length > 0 ? Integer.parseInt(args[0]) : 20;
        Path tron = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        Network lamp = ModelLoader.load(tron.resolve("LightContr.xml"));
        Path dir = Files.createTempDirectory("coverage-bench");
        Network street = ModelLoader.load(StreetLightModel.write(dir, 2));
        List<Bench> benches = List.of(
                new Bench("LightContr + SmartLamp", lamp, TestInterface.fromFile(lamp, tron.resolve("LightContr.trn")),
                        SmartLamp::new, TestOptions.defaults(0).withTimeout(100_000)),
                new Bench("street light (2 operators) + SimulatedStreetLights", street, TestInterface.fromNames(street),
                        () -> new SimulatedStreetLights(false),
                        TestOptions.defaults(0).withTimeUnit(StreetLightModel.TIME_UNIT_MICROS).withTimeout(100_000)));
        for (Bench b : benches) {
            for (Variant v : VARIANTS) {
                Strategy strategy = v.strategy();
                List<Double> units = new ArrayList<>();
                List<Integer> inputs = new ArrayList<>();
                int missed = 0;
                int environmentEdges = 0;
                for (long seed = 1; seed <= seeds; seed++) {
                    TestOptions o = new TestOptions(seed, b.options().timeUnitMicros(), b.options().timeout(),
                            v.policy(), v.bound(), true);
                    OnlineTester t = new OnlineTester(b.network(), b.iface(), b.system().get(), o)
                            .steer(new Steering(strategy, List.of(), Steering.DEFAULT_HORIZON, -1, false));
                    TestResult r = t.run();
                    if (r.verdict() != Verdict.PASSED) {
                        throw new IllegalStateException(b.name() + " seed " + seed + ": " + r);
                    }
                    SteeringReport s = t.steeringReport();
                    environmentEdges = s.environmentEdges();
                    if (s.environmentCoveredMicros() < 0) {
                        missed++;
                        units.add(Double.POSITIVE_INFINITY);
                        inputs.add(Integer.MAX_VALUE);
                    } else {
                        units.add(s.environmentCoveredMicros() / (double) o.timeUnitMicros());
                        inputs.add(s.environmentCoveredInputs());
                    }
                }
                units.sort(null);
                inputs.sort(null);
                System.out.printf("%s, %s: %d environment edges; time units to cover them: median %s, slowest %s;"
                                + " inputs: median %s, most %s; %d of %d seeds not within %d units%n", b.name(),
                        v.name(), environmentEdges, show(median(units)),
                        show(units.get(units.size() - 1)), showInt(inputs.get(inputs.size() / 2)),
                        showInt(inputs.get(inputs.size() - 1)), missed, seeds, b.options().timeout());
            }
        }
    }

    private static double median(List<Double> sorted) {
        int n = sorted.size();
        return n % 2 == 1 ? sorted.get(n / 2) : (sorted.get(n / 2 - 1) + sorted.get(n / 2)) / 2;
    }

    private static String show(double v) {
        return Double.isInfinite(v) ? "not reached" : String.format("%.1f", v);
    }

    private static String showInt(int v) {
        return v == Integer.MAX_VALUE ? "not reached" : Integer.toString(v);
    }
}
