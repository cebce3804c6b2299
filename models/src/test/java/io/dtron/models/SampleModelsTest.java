package io.dtron.models;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.List;
import org.junit.jupiter.api.Test;

/** The sample models that ship with DTRON load, with the interfaces their documentation promises. */
class SampleModelsTest {

    @Test
    void tickerHasAResetInputAndANumberedTickOutput() throws ModelException {
        Network n = ModelLoader.loadResource(getClass().getClassLoader(), "io/dtron/models/ticker.xml");
        assertTrue(n.warnings().isEmpty(), n.warnings().toString());
        assertEquals(List.of("Ticker", "Environment"), n.templates());
        TestInterface i = TestInterface.fromNames(n);
        assertEquals("reset", i.inputs().get(0).name());
        assertEquals(1, i.inputs().size());
        TestInterface.ObservableChannel tick = i.output("tick").orElseThrow();
        assertEquals(List.of("seq"), tick.variables().stream().map(TestInterface.AttachedVariable::name).toList());
        assertEquals(2, n.queries().size());
    }
}
