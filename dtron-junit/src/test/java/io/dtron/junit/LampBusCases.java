package io.dtron.junit;

import io.dtron.api.ChildJvm;
import io.dtron.junit.internal.DtronExtension;
import java.nio.file.Files;
import java.nio.file.Path;

/**
 * Test classes with {@code @DtronTest} methods over the bus that {@link DtronTestTest} runs through the JUnit
 * Platform: the lamp behind a bus adapter, a member of a fresh JGroups bus on loopback, in real time at 50 ms per
 * time unit (the correct lamp shows its level in the middle of the 1 to 2 units the model allows, 25 ms from either
 * end).
 */
final class LampBusCases {
    private LampBusCases() {
    }

    /** The correct lamp, two seeds from 10, 40 time units each. */
    static class Correct {
        @DtronTest(model = "lamp.xta", seeds = 2, seed = 10, timeout = 40, timeUnit = 50_000)
        void lamp(DtronBusRun run) {
            run.test(new LampBusAdapter(1.5));
        }
    }

    /** The correct lamp steered toward a goal it reaches after its second press. */
    static class Goal {
        @DtronTest(model = "lamp.xta", seeds = 1, seed = 5, timeout = 100, timeUnit = 50_000,
                goals = "E<> Lamp.Switching and Lamp.level == 0")
        void lamp(DtronBusRun run) {
            run.test(new LampBusAdapter(1.5));
        }
    }

    /** The late lamp (3 time units), one new seed every time. */
    static class Late {
        @DtronTest(model = "lamp.xta", seeds = 1, timeout = 40, timeUnit = 50_000)
        void lamp(DtronBusRun run) {
            run.test(new LampBusAdapter(3));
        }
    }

    /**
     * The correct lamp in a JVM of its own, which joins the run's bus by its name; its output goes to {@code
     * lamp-process.log} in the folder of the reports.
     */
    static class OtherProcess {
        @DtronTest(model = "lamp.xta", seeds = 1, seed = 30, timeout = 40, timeUnit = 50_000)
        void lamp(DtronBusRun run) throws Exception {
            Path log = Path.of(System.getProperty(DtronExtension.REPORT_DIRECTORY)).resolve("lamp-process.log");
            Files.createDirectories(log.getParent());
            try (ChildJvm lamp = ChildJvm.start(LampProcess.class, log, run.cluster())) {
                run.test();
            }
        }
    }

    /** No adapter on the bus: the run waits a second for one that serves the model's channels. */
    static class NoAdapter {
        @DtronTest(model = "lamp.xta", seeds = 1, seed = 1, timeUnit = 50_000, busWait = 1)
        void lamp(DtronBusRun run) {
            run.test();
        }
    }
}
