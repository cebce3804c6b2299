package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.bench.GeneratedModels;
import org.junit.jupiter.api.Test;

/** The benchmark's generated models are valid and as large as the benchmark says. */
class GeneratedModelsTest {

    @Test
    void manyProcessesExpandsToOneProcessPerIdentifierPlusTheServer() throws ModelException {
        Network n = ModelLoader.load("many.xml", GeneratedModels.manyProcesses(1000));
        assertEquals(1001, n.processes().size());
        assertEquals("Worker(999)", n.processes().get(999).name());
        assertEquals(1001, n.clockCount());
        assertEquals(2001, n.channelCount());
    }

    @Test
    void largeFileIsAboutOneMegabyteAndLoads() throws ModelException {
        String text = GeneratedModels.largeFile(1 << 20);
        assertTrue(text.length() >= (1 << 20) && text.length() <= (1 << 20) + (16 << 10), "size " + text.length());
        Network n = ModelLoader.load("large.xml", text);
        assertTrue(n.processes().size() > 50, "processes " + n.processes().size());
        assertEquals(40, n.processes().get(0).edges().size());
    }

    @Test
    void editorFileIsAboutOneMegabyteOfTemplatesWithEveryKindOfLabelAndLoads() throws ModelException {
        String text = GeneratedModels.editorFile(1 << 20);
        assertTrue(text.length() >= (1 << 20) && text.length() <= (1 << 20) + (32 << 10), "size " + text.length());
        Network n = ModelLoader.load("editor.xml", text);
        assertTrue(n.processes().size() > 30, "processes " + n.processes().size());
        Process p = n.processes().get(0);
        assertEquals(30, p.locations().size());
        assertEquals(45, p.edges().size());
        assertTrue(p.edges().stream().anyMatch(e -> !e.selects().isEmpty() && e.sync() != null && e.guard() != null
                && !e.updates().isEmpty()), "an edge with all four kinds of labels");
    }

    @Test
    void largeDeclarationsIsAboutOneMegabyteOfGlobalDeclarationsAndLoads() throws ModelException {
        String text = GeneratedModels.largeDeclarations(1 << 20);
        assertTrue(text.length() >= (1 << 20) && text.length() <= (1 << 20) + (4 << 10), "size " + text.length());
        Network n = ModelLoader.load("declarations.xml", text);
        assertEquals(1, n.processes().size());
        assertTrue(n.functions().size() > 1000, "functions " + n.functions().size());
    }
}
