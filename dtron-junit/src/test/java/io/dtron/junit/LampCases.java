package io.dtron.junit;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.engine.TestResult;

/**
 * Test classes with {@code @DtronTest} methods that {@link DtronTestTest} runs through the JUnit Platform (their
 * names do not end in Test, so that Surefire does not run them by themselves).
 */
final class LampCases {
    private LampCases() {
    }

    /** The correct lamp, five seeds from 100. */
    static class Correct {
        @DtronTest(model = "lamp.xta", seeds = 5, seed = 100)
        void lamp(DtronRun run) {
            run.test(new Lamp(false));
        }
    }

    /** The correct lamp, one seed, 50 time units of 500 us. */
    static class Short {
        @DtronTest(model = "lamp.xta", seeds = 1, seed = 5, timeout = 50, timeUnit = 500)
        void lamp(DtronRun run) {
            assertEquals(5, run.seed());
            assertEquals(java.util.Optional.empty(), run.goal());
            TestResult result = run.test(new Lamp(false));
            assertEquals(50 * 500, result.durationMicros());
        }
    }

    /** The correct lamp against a model with a TRON interface file, which gives the time unit and the timeout. */
    static class TronInterface {
        @DtronTest(model = "tron-lamp.xta", interfaceFile = "tron-lamp.trn", seeds = 1, seed = 3)
        void lamp(DtronRun run) {
            run.test(new Lamp(false));
        }
    }

    /** The lamp in real time, for 2 time units of 250 ms: less than the user waits before the first press. */
    static class RealTime {
        @DtronTest(model = "lamp.xta", seeds = 1, seed = 1, timeout = 2, timeUnit = 250_000, virtualTime = false)
        void lamp(DtronRun run) {
            run.test(new Lamp(false));
        }
    }

    /** The late lamp, three seeds from 7. */
    static class Late {
        @DtronTest(model = "lamp.xta", seeds = 3, seed = 7)
        void lamp(DtronRun run) {
            run.test(new Lamp(true));
        }
    }

    /** The late lamp, two new seeds every time. */
    static class LateNewSeeds {
        @DtronTest(model = "lamp.xta", seeds = 2)
        void lamp(DtronRun run) {
            run.test(new Lamp(true));
        }
    }

    /** The correct lamp, new seeds every time. */
    static class CorrectNewSeeds {
        @DtronTest(model = "lamp.xta", seeds = 2)
        void lamp(DtronRun run) {
            run.test(new Lamp(false));
        }
    }

    /** Two goals, one the lamp reaches, one no run can reach (the user presses at most 10 units apart). */
    static class Goals {
        @DtronTest(model = "/io/dtron/junit/lamp.xta", seeds = 2, seed = 1,
                goals = {"E<> Lamp.Switching and Lamp.level == 0", "E<> User.u > 20"})
        void lamp(DtronRun run) {
            run.test(new Lamp(false));
        }
    }

    /**
     * Mistakes: a model that is not there, one with a syntax error, a method without a DtronRun, a method that tests
     * nothing.
     */
    static class Mistakes {
        @DtronTest(model = "broken.xta")
        void brokenModel(DtronRun run) {
            run.test(new Lamp(false));
        }

        @DtronTest(model = "no-such-lamp.xta")
        void missingModel(DtronRun run) {
            run.test(new Lamp(false));
        }

        @DtronTest(model = "lamp.xta")
        void noRun() {
        }

        @DtronTest(model = "lamp.xta", seeds = 1)
        void testsNothing(DtronRun run) {
        }
    }
}
