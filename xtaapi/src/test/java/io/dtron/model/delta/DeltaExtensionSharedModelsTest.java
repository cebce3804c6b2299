package io.dtron.model.delta;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ChannelVariable;
import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Location;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.model.TestInterface.ObservableChannel;
import io.dtron.model.delta.DeltaExtension.Delay;
import io.dtron.xta.SharedModels;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.stream.Stream;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

/**
 * Every shared model that loads, with each of its global channels made an input or an output, is widened into a
 * model that loads again with the same processes, locations and edges, whose clock bounds only grew.
 */
class DeltaExtensionSharedModelsTest {

    static Stream<Path> models() {
        return SharedModels.modelFiles().stream();
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("models")
    void widenedModelsLoadAgainWithBoundsThatOnlyGrew(Path file) throws ModelException {
        String text = SharedModels.read(file);
        Network before;
        try {
            before = ModelLoader.load(file.toString(), text);
        } catch (ModelException rejected) {
            return; // SharedModelsLoadTest checks why
        }
        List<ObservableChannel> inputs = new ArrayList<>();
        List<ObservableChannel> outputs = new ArrayList<>();
        Map<String, Delay> delays = new HashMap<>();
        for (ChannelVariable c : before.channels()) {
            for (int k = 0; c.owner() == null && k < c.type().channels(); k++) {
                String name = c.elementName(c.index() + k);
                (delays.size() % 2 == 0 ? inputs : outputs).add(new ObservableChannel(name, c.index() + k, name,
                        List.of()));
                delays.put(name, new Delay(1500, 2500));
            }
        }
        if (delays.isEmpty()) {
            return;
        }
        DeltaExtension.Result r = DeltaExtension.extend(before, text, new TestInterface(inputs, outputs, null, null),
                delays, 1000, "a test");
        Network after = ModelLoader.load(file + " (Delta-extended)", r.text());
        assertEquals(before.processes().size(), after.processes().size());
        int grown = 0;
        for (int p = 0; p < before.processes().size(); p++) {
            List<Edge> edges = before.processes().get(p).edges();
            List<Location> locations = before.processes().get(p).locations();
            assertEquals(edges.size(), after.processes().get(p).edges().size());
            assertEquals(locations.size(), after.processes().get(p).locations().size());
            for (int e = 0; e < edges.size(); e++) {
                grown += compare(edges.get(e).guard(), after.processes().get(p).edges().get(e).guard());
            }
            for (int l = 0; l < locations.size(); l++) {
                grown += compare(locations.get(l).invariant(), after.processes().get(p).locations().get(l).invariant());
            }
        }
        assertTrue(r.changes().isEmpty() == (grown == 0), file + ": " + r.changes().size() + " changes, " + grown
                + " grown bounds");
    }

    /** How many clock bounds grew from {@code before} to {@code after}; fails when one shrank. */
    private static int compare(Expression before, Expression after) {
        List<Integer> old = new ArrayList<>();
        List<Integer> now = new ArrayList<>();
        bounds(before, old);
        bounds(after, now);
        if (old.size() != now.size()) {
            return 1; // x == c became two bounds
        }
        int grown = 0;
        for (int i = 0; i < old.size(); i++) {
            assertTrue(now.get(i) >= old.get(i), before.pos() + ": " + old + " -> " + now);
            grown += now.get(i) > old.get(i) ? 1 : 0;
        }
        return grown;
    }

    private static void bounds(Expression e, List<Integer> out) {
        if (e instanceof Expression.Binary b && (b.op() == Expression.Operator.AND
                || b.op() == Expression.Operator.OR)) {
            bounds(b.left(), out);
            bounds(b.right(), out);
        } else if (e instanceof Expression.Binary b && b.right() instanceof Expression.Constant c
                && b.left().type() instanceof io.dtron.model.Type.Clock) {
            out.add(c.value());
        } else if (e instanceof Expression.Binary b && b.left() instanceof Expression.Constant c
                && b.right().type() instanceof io.dtron.model.Type.Clock) {
            out.add(c.value());
        }
    }
}
