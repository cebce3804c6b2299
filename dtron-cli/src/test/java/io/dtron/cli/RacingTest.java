package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import java.io.InputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Inputs in a window of 2 time units, racing the system's timeout, on a bus, with the system's adapter in a JVM of
 * its own ({@code racing.xta}, {@link RacingAdapterMain}), at 10 ms per unit: a correct system is never FAILED (unless
 * a busy machine held its JVM up past a deadline, which it says), and
 * one that answers 2 units after its deadline is whenever its input landed in time (a loaded machine may deliver
 * it late, which is INCONCLUSIVE, saying so). How often the correct one PASSES depends on the load and is
 * counted outside the test command ({@code scripts/racing-stats.sh}, figures in benchmarks.md).
 */
@Timeout(value = 5, unit = TimeUnit.MINUTES)
class RacingTest {
    private static final int RUNS = 3;

    @TempDir
    Path dir;

    private Path model() throws Exception {
        Path model = dir.resolve("racing.xta");
        try (InputStream in = RacingTest.class.getResourceAsStream("racing.xta")) {
            Files.write(model, in.readAllBytes());
        }
        return model;
    }

    /** The runs against one adapter JVM of the variant; {@link #adapterLog} holds what that JVM printed. */
    private CommandRun[] runs(String variant) throws Exception {
        Path model = model();
        String cluster = "racing-" + UUID.randomUUID().toString().substring(0, 8);
        CommandRun[] runs = new CommandRun[RUNS];
        try (ChildJvm adapter = ChildJvm.start(RacingAdapterMain.class, dir.resolve(variant + ".log"), cluster,
                variant)) {
            adapter.awaitOutput("joined", Duration.ofSeconds(60));
            for (int i = 0; i < RUNS; i++) {
                runs[i] = CommandRun.of("run", model.toString(), "--cluster", cluster, "--timeunit", "10000",
                        "--timeout", "60", "--seed", String.valueOf(i + 1));
            }
            adapterLog = adapter.output();
        }
        return runs;
    }

    private String adapterLog = "";

    @Test
    void aCorrectSystemIsNeverFailedAndTheRunSaysHowItProbedAndWhereInputsGo() throws Exception {
        CommandRun[] runs = runs("correct");
        for (CommandRun r : runs) {
            // a busy machine can hold the adapter's JVM up past the model's deadline: then FAILED is true of the
            // system as it ran, and the adapter, timing its outputs on its own run clock, said so; a FAILED verdict
            // without that warning is a false one
            if (r.exit() == 2) {
                assertTrue(adapterLog.contains("this JVM was held up"), "FAILED, yet the adapter sent every output"
                        + " in time: " + r.out() + r.err() + "\nadapter: " + adapterLog);
            }
            assertTrue(r.out().matches("(?s).*dtron run: probed the adapters in \\d+ rounds over [0-9.]+ s while the"
                    + " engine warmed up, each probe an input that reaches no listener, until (their round trips were"
                    + " steady|the limit, their round trips still uneven) \\(the last rounds' round trips up to [0-9.]+"
                    + " ms\\).*"), r.out());
            assertTrue(r.out().contains("inside the end of their windows, and each input channel's delay to its"
                    + " adapter further inside"), r.out());
        }
    }

    @Test
    void aSystemThatAnswersAfterItsDeadlineFailsEveryRunItsInputLandedIn() throws Exception {
        CommandRun[] runs = runs("late");
        for (CommandRun r : runs) {
            // an input that a loaded machine delivered after its window closed, or that the tester's held-up thread
            // came to after it, makes the run INCONCLUSIVE first (saying so); every other run is FAILED, never PASSED
            if (r.exit() == 3) {
                assertTrue(r.out().contains("(input executed too late)")
                        || r.out().contains("(too late for the window the environment allowed)"), r.out());
            } else {
                assertEquals(2, r.exit(), r.out() + r.err());
                assertTrue(r.out().contains("FAILED: "), r.out());
            }
        }
    }
}
