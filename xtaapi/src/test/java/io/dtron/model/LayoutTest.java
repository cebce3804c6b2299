package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import org.junit.jupiter.api.Test;

/** The saved drawing of a model, numbered as the loaded network. */
class LayoutTest {
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");

    @Test
    void theLampsDrawingHasEveryLocationAndEdgeOfItsProcessesWithTheirSavedPositions() throws Exception {
        Path file = SHARED.resolve("tron/LightContr.xml");
        Network network = ModelLoader.load(file);
        Layout layout = Layout.read(file);
        int nails = 0;
        for (Process p : network.processes()) {
            Layout.Template t = layout.template(p.template()).orElseThrow();
            assertTrue(t.positioned(), t.name());
            assertEquals(p.locations().size(), t.locations().size(), p.name());
            assertEquals(p.edges().size(), t.edges().size(), p.name());
            for (Location l : p.locations()) {
                assertEquals(l.name(), t.locations().get(l.index()).name());
                assertNotNull(t.locations().get(l.index()).at());
            }
            for (Edge e : p.edges()) {
                assertEquals(e.source(), t.edges().get(e.index()).source());
                assertEquals(e.target(), t.edges().get(e.index()).target());
            }
            assertEquals(p.initial(), t.locations().stream().filter(Layout.Location::initial).findFirst()
                    .map(t.locations()::indexOf).orElse(-1), p.name());
            nails += t.edges().stream().mapToInt(e -> e.nails().size()).sum();
        }
        assertTrue(nails > 0, "the lamp's edges have bend points");
        Layout.Location idle = layout.template("Interface").orElseThrow().locations().get(0);
        assertTrue(idle.labels().stream().anyMatch(l -> l.kind().equals("name") && l.at() != null), idle.toString());
    }

    @Test
    void aTextualModelHasNoPositionsButItsLabelsAsWritten() throws Exception {
        Layout layout = Layout.of("lamp.xta", """
                chan press;
                process Lamp {
                    clock x;
                    state off, low { x <= 5 };
                    init off;
                    trans off -> low { guard x > 1; sync press?; assign x = 0; };
                }
                system Lamp;
                """);
        Layout.Template lamp = layout.template("Lamp").orElseThrow();
        assertFalse(lamp.positioned());
        assertNull(lamp.locations().get(0).at());
        assertEquals("x <= 5", lamp.locations().get(1).labels().get(0).text());
        assertEquals(java.util.List.of("guard", "synchronisation", "assignment"), lamp.edges().get(0).labels().stream()
                .map(Layout.Label::kind).toList());
        assertEquals("press?", lamp.edges().get(0).labels().get(1).text());
    }

    @Test
    void aModelThatDoesNotParseIsAModelError() {
        assertThrows(ModelException.class, () -> Layout.of("bad.xta", "process {"));
        assertThrows(ModelException.class, () -> Layout.read(Path.of("no-such-model.xml")));
    }
}
