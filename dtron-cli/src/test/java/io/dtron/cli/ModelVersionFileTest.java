package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.control.ModelVersion;
import io.dtron.model.ModelLoader;
import io.dtron.model.TestInterface;
import io.dtron.testsupport.Waits;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The file of new model versions of {@code dtron control --reload-from}, on real files and the platform's watch
 * service, with the robot-arm sample: checked when the run starts, then whenever a version is moved into place;
 * a version that breaks the sample's queries is refused, one that keeps them accepted, one that does not load said
 * so; a version's own .q file is used before the started model's.
 */
class ModelVersionFileTest {
    private static final Path SAMPLE = Path.of("../models/src/main/resources/io/dtron/models/robotarm");

    private static final class Outcomes implements ModelVersionFile.Sink {
        final List<String> seen = new CopyOnWriteArrayList<>();

        @Override
        public void checked(ModelVersion.Check check) {
            seen.add(check.accepted() ? "accepted" : "refused: " + check.refusal());
        }

        @Override
        public void unloadable(String version, String reason) {
            seen.add("unloadable: " + reason);
        }
    }

    /** Writes {@code text} beside {@code target} and moves it into place whole, as the page says to. */
    private static void moveIn(Path target, String text) throws Exception {
        Path next = Files.writeString(target.resolveSibling(".next-" + target.getFileName()), text);
        Files.move(next, target, StandardCopyOption.ATOMIC_MOVE, StandardCopyOption.REPLACE_EXISTING);
    }

    @Test
    void aVersionIsCheckedAtTheStartAndWheneverOneIsMovedIntoPlace(@TempDir Path dir) throws Exception {
        Path model = Files.copy(SAMPLE.resolve("robot-arm.xta"), dir.resolve("robot-arm.xta"));
        Files.copy(SAMPLE.resolve("robot-arm.q"), dir.resolve("robot-arm.q"));
        Path version = Files.copy(SAMPLE.resolve("robot-arm-slow.xta"), dir.resolve("next.xta"));
        TestInterface running = TestInterface.fromNames(ModelLoader.load(model));
        Outcomes outcomes = new Outcomes();
        try (ModelVersionFile file = new ModelVersionFile(version, model, null, running, outcomes)) {
            file.checkNow();
            assertEquals(List.of("refused: query [2] A[] (Arm.Moving imply Arm.y <= 5) is NOT satisfied"),
                    outcomes.seen, "the slower arm, checked with the started model's .q");
            file.watch();
            moveIn(version, Files.readString(SAMPLE.resolve("robot-arm-v2.xta")));
            Waits.await("version 2 checked").until(() -> outcomes.seen.size() == 2);
            assertEquals("accepted", outcomes.seen.get(1));
            moveIn(version, "chan i_move;;");
            Waits.await("a broken version checked").until(() -> outcomes.seen.size() == 3);
            assertTrue(outcomes.seen.get(2).startsWith("unloadable: it does not load: "), outcomes.seen.toString());
            // a version with a .q of its own is checked with it: version 2 with a query it breaks
            Files.writeString(dir.resolve("next.q"), "A[] Controller.c <= 4\n");
            moveIn(version, Files.readString(SAMPLE.resolve("robot-arm-v2.xta")));
            Waits.await("version 2 with its own queries checked").until(() -> outcomes.seen.size() == 4);
            assertEquals("refused: query [1] A[] Controller.c <= 4 is NOT satisfied", outcomes.seen.get(3));
        }
    }

    @Test
    void aVersionWithoutQueriesAnywhereIsRefused(@TempDir Path dir) throws Exception {
        Path model = Files.copy(SAMPLE.resolve("robot-arm.xta"), dir.resolve("robot-arm.xta"));
        Path version = Files.copy(SAMPLE.resolve("robot-arm-v2.xta"), dir.resolve("v2.xta"));
        Outcomes outcomes = new Outcomes();
        new ModelVersionFile(version, model, null, TestInterface.fromNames(ModelLoader.load(model)), outcomes)
                .checkNow();
        assertEquals(List.of("refused: it has no queries (a .q file beside it, or in the model) to check it with"),
                outcomes.seen);
    }
}
