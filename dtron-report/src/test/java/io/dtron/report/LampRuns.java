package io.dtron.report;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.model.Layout;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.file.Path;

/**
 * Runs of the smart lamp of TRON's manual ({@code ../shared/models/tron/LightContr.xml}) in virtual time against the
 * model's own implementation part, recorded for a report.
 */
final class LampRuns {
    static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
    static final Path MODEL = SHARED.resolve("tron/LightContr.xml");

    private LampRuns() {
    }

    /** A record of a run of the lamp, not yet run. */
    static RunRecord record() throws Exception {
        return new RunRecord(MODEL.toString(), network(), Layout.read(MODEL), null);
    }

    static Network network() throws Exception {
        return ModelLoader.load(MODEL);
    }

    /** Runs the lamp for {@code units} time units with {@code seed}, recording into {@code record}. */
    static TestResult run(RunRecord record, long seed, long units) throws Exception {
        return run(record, seed, units, DelayPolicy.RANDOM);
    }

    /** Runs the lamp with inputs timed by {@code policy}. */
    static TestResult run(RunRecord record, long seed, long units, DelayPolicy policy) throws Exception {
        Network network = network();
        TestInterface lamp = TestInterface.fromFile(network, SHARED.resolve("tron/LightContr.trn"));
        TestOptions options = new TestOptions(seed, 1000, units, policy, 0, true);
        OnlineTester tester = new OnlineTester(network, lamp, new ModelSystem(network, lamp, seed), options);
        tester.coverableBudget(java.time.Duration.ZERO);
        record.start(seed, 1000, units, true);
        tester.addListener(new RunRecorder(record));
        return tester.run();
    }
}
