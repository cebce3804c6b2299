package io.dtron.model;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.util.Collections;
import java.util.concurrent.atomic.AtomicReference;
import org.junit.jupiter.api.Test;

/**
 * Models nested up to the front end's limit load even from a thread with a small stack (the load runs on a
 * large one); past the limit they are model errors.
 */
class DeepNestingTest {
    private static final String SUM = String.join(" + ", Collections.nCopies(990, "c"));

    private static String model(String declarations, String guard) {
        return "<nta><declaration>int v;\nconst int c = 0;\n" + declarations + "</declaration>\n<template><name>P</name>"
                + "<location id=\"a\"/><init ref=\"a\"/>\n<transition><source ref=\"a\"/><target ref=\"a\"/>"
                + "<label kind=\"guard\">" + guard + "</label></transition></template>\n"
                + "<system>system P;</system></nta>";
    }

    /** Runs {@code load} on a thread with a 256 KB stack, a quarter of the default. */
    private static Object onSmallStack(ModelLoad load) throws InterruptedException {
        AtomicReference<Object> result = new AtomicReference<>();
        Thread t = new Thread(null, () -> {
            try {
                result.set(load.run());
            } catch (ModelException | RuntimeException | Error e) {
                result.set(e);
            }
        }, "small-stack", 256 << 10);
        t.start();
        t.join();
        return result.get();
    }

    private interface ModelLoad {
        Network run() throws ModelException;
    }

    @Test
    void nestingUpToTheLimitLoadsFromASmallStack() throws InterruptedException {
        String model = model("int x = " + "(".repeat(990) + "1" + ")".repeat(990) + ";\nint y = " + SUM + ";\n"
                + "int f() { " + "if (v == 0) ".repeat(900) + "return 1; return 0; }", SUM + " == 0 &amp;&amp; f() == 1");
        Object loaded = onSmallStack(() -> ModelLoader.load("deep.xml", model));
        Network network = assertInstanceOfNetwork(loaded);
        assertEquals(1, network.processes().size());
    }

    private static Network assertInstanceOfNetwork(Object loaded) {
        if (loaded instanceof Throwable t) {
            throw new AssertionError("the model did not load: " + t, t);
        }
        return (Network) loaded;
    }

    @Test
    void fourThousandParenthesesAreAModelErrorWithTheLimit() {
        String model = model("int x = " + "(".repeat(4000) + "1" + ")".repeat(4000) + ";", "true");
        ModelException e = assertThrows(ModelException.class, () -> ModelLoader.load("deep.xml", model));
        assertEquals(1, e.errors().size());
        assertEquals("deep.xml:3:1009: error: expression nested deeper than the limit of 1000 levels"
                + " (declaration, column 1009)", e.errors().get(0).format());
    }
}
