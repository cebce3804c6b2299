package io.dtron.engine.internal.eval;

import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.Variable;
import java.util.Arrays;
import java.util.stream.Collectors;
import java.util.stream.Stream;

/** Test support: a loaded model, an evaluator for it and a state vector starting at the initial state. */
final class TestModel {
    final Network network;
    final Evaluator evaluator;
    final int[] vars;
    final ClockResets resets = new ClockResets();

    private TestModel(Network network) {
        this.network = network;
        this.evaluator = new Evaluator(network);
        this.vars = network.initialState();
    }

    /** Loads a whole XTA text. */
    static TestModel load(String xta) {
        try {
            return new TestModel(ModelLoader.load("t.xta", xta));
        } catch (ModelException e) {
            throw new AssertionError(e.getMessage(), e);
        }
    }

    /** Global {@code declarations} and one process P with a location A and one edge A -> A per body. */
    static TestModel of(String declarations, String... edgeBodies) {
        String edges = Stream.of(edgeBodies).map(b -> "A -> A { " + b + " }").collect(Collectors.joining(", "));
        return load(declarations + "\nprocess P() {\n state A;\n init A;\n"
                + (edgeBodies.length == 0 ? "" : " trans " + edges + ";\n") + "}\nsystem P;\n");
    }

    /** Global {@code declarations} and one guard per expression; see {@link #guard}. */
    static TestModel guards(String declarations, String... guards) {
        return of(declarations, Stream.of(guards).map(g -> "guard " + g + ";").toArray(String[]::new));
    }

    /** The value of the single expression {@code expression} over the globals {@code declarations}. */
    static int value(String declarations, String expression) {
        return guards(declarations, expression).guard(0);
    }

    Process process(String name) {
        return network.process(name).orElseThrow();
    }

    /** Edge {@code k} of the first process. */
    Edge edge(int k) {
        return network.processes().get(0).edges().get(k);
    }

    /** The value of the guard of edge {@code k}, with the select bindings {@code frame}. */
    int guard(int k, int... frame) {
        return evaluator.evaluate(edge(k).guard(), vars, frame);
    }

    /** Runs the updates of edge {@code k} with the select bindings {@code frame}; resets go to {@link #resets}. */
    TestModel run(int k, int... frame) {
        return run(edge(k), frame);
    }

    TestModel run(Edge edge, int... frame) {
        for (Expression u : edge.updates()) {
            evaluator.execute(u, vars, frame, resets);
        }
        return this;
    }

    Variable variable(String name) {
        return network.variable(name).orElseThrow(() -> new AssertionError("no variable " + name));
    }

    /** The value of a one-slot variable. */
    int get(String name) {
        return vars[variable(name).offset()];
    }

    /** The slots of a variable. */
    int[] slots(String name) {
        Variable v = variable(name);
        return Arrays.copyOfRange(vars, v.offset(), v.offset() + v.size());
    }

    /** The resets recorded, as {@code "clock=value"} items. */
    String resets() {
        StringBuilder sb = new StringBuilder();
        for (int i = 0; i < resets.size(); i++) {
            sb.append(i == 0 ? "" : " ").append(resets.clock(i)).append('=').append(resets.value(i));
        }
        return sb.toString();
    }
}
