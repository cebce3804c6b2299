package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * A channel array named in a TRON interface file gives one channel per element, named as in the model, as an array
 * named {@code i_...} does by the naming convention: so that models such as Uppaal's train-gate, whose trains and gate
 * talk on arrays of channels, can be tested with an interface file.
 */
class InterfaceArraysTest {
    private static final String MODEL = """
            const int N = 3;
            chan appr[N], stop[N];
            int id;
            process Train() { state S; init S; trans S -> S { sync appr[0]!; }; }
            process Gate() { state S; init S; trans S -> S { sync appr[0]?; }; }
            system Train, Gate;
            """;

    @Test
    void anArrayGivesOneChannelPerElement() throws ModelException {
        Network n = ModelLoader.load("m.xta", MODEL);
        TestInterface t = TestInterface.fromText(n, "m.trn", """
                input appr(id);
                output stop();
                """);
        assertEquals(List.of("appr[0]", "appr[1]", "appr[2]"),
                t.inputs().stream().map(TestInterface.ObservableChannel::name).toList());
        assertEquals(List.of("stop[0]", "stop[1]", "stop[2]"),
                t.outputs().stream().map(TestInterface.ObservableChannel::name).toList());
        int first = n.channel("appr").orElseThrow().index();
        assertEquals(List.of(first, first + 1, first + 2),
                t.inputs().stream().map(TestInterface.ObservableChannel::channel).toList());
        assertEquals("appr[2]", n.channelName(t.input("appr[2]").orElseThrow().channel()));
        assertEquals("id", t.input("appr[1]").orElseThrow().variables().get(0).name(), "attached to every element");
    }
}
