package io.dtron.engine.sim;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;

class ModelSystemTest {
    static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");

    static TestResult run(Network n, TestInterface ti, long seed, long simSeed, long timeout, DelayPolicy policy) {
        TestOptions o = new TestOptions(seed, 1000, timeout, policy, 0, true);
        return new OnlineTester(n, ti, new ModelSystem(n, ti, simSeed), o).run();
    }

    /** Every seed and delay policy PASSES, and the system produced outputs in the runs. */
    static void passesForSeeds(Network n, TestInterface ti, long timeout) {
        long outputs = 0;
        for (long seed = 1; seed <= 30; seed++) {
            for (DelayPolicy policy : DelayPolicy.values()) {
                TestResult r = run(n, ti, seed, seed * 7919, timeout, policy);
                assertEquals(Verdict.PASSED, r.verdict(), "seed " + seed + " " + policy + ": " + r.explanation());
                outputs += r.outputs();
            }
        }
        org.junit.jupiter.api.Assertions.assertTrue(outputs > 0, "no output in any run");
    }

    @Test
    void smallModelsAsTheirOwnSystemsPassForEverySeed() throws Exception {
        for (String name : List.of("beeper.xta", "starter.xta", "chooser.xta")) {
            Network n = MutantsTest.load(name);
            passesForSeeds(n, TestInterface.fromNames(n), 200);
        }
    }

    @Test
    void theBundledTickerAsItsOwnSystemPassesForEverySeed() throws Exception {
        Network n = ModelLoader.load(Path.of("../models/src/main/resources/io/dtron/models/ticker.xml"));
        passesForSeeds(n, TestInterface.fromNames(n), 2000);
    }

    @Test
    void uppaalsBoxesWithAnInterfaceAsItsOwnSystemPassesForEverySeed() throws Exception {
        // Guard's ok starts a box; the boxes' sensors report blck and red
        Network n = ModelLoader.load(SHARED.resolve("uppaal-examples/boxes.xml"));
        passesForSeeds(n, TestInterface.fromText(n, "boxes.trn", "input ok(); output blck(), red();"), 1000);
    }

    @Test
    void theChooserAnswersEveryValueItsSelectAllows() throws Exception {
        Network n = MutantsTest.load("chooser.xta");
        TestInterface ti = TestInterface.fromNames(n);
        java.util.Set<Integer> values = new java.util.TreeSet<>();
        for (long seed = 1; seed <= 10; seed++) {
            TestOptions o = new TestOptions(seed, 1000, 100, DelayPolicy.RANDOM, 0, true);
            OnlineTester tester = new OnlineTester(n, ti, new ModelSystem(n, ti, seed), o);
            tester.addListener(new io.dtron.engine.TestListener() {
                @Override
                public void outputObserved(io.dtron.engine.Event output, long micros) {
                    values.add(output.value("v"));
                }
            });
            assertEquals(Verdict.PASSED, tester.run().verdict());
        }
        assertEquals(java.util.Set.of(1, 2, 3), values, "the simulated system chose each value the select allows");
    }

    @Test
    void aClockNeverResetEndsTheRunInconclusiveWhenItOutgrowsTheZones() throws Exception {
        // the starter's x is never reset after go: at 1000 ticks per unit it can count to 536,870 units
        Network n = MutantsTest.load("starter.xta");
        TestResult r = run(n, TestInterface.fromNames(n), 1, 1, 600_000, DelayPolicy.RANDOM);
        assertEquals(Verdict.INCONCLUSIVE, r.verdict(), r.explanation());
        org.junit.jupiter.api.Assertions.assertTrue(r.explanation().startsWith("the model as system under test cannot"
                + " count a clock past 536870 time units"), r.explanation());
    }

    @Test
    void theLightControllerAsItsOwnSystemPassesForEverySeed() throws Exception {
        Network n = ModelLoader.load(SHARED.resolve("tron/LightContr.xml"));
        passesForSeeds(n, TestInterface.fromFile(n, SHARED.resolve("tron/LightContr.trn")), 2000);
    }
}
